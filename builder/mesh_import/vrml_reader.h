#pragma once
// VRML97 (VRML 2.0, ISO/IEC 14772-1) scenes of meshes in: what `bodygen export`
// writes and BodyView's saved scenes use. Debian's assimp 5.2 reads only VRML 1.0.
//
// Reads: the "#VRML V2.0 utf8" header, comments, DEF/USE, Transform (translation,
// rotation axis-angle, scale, center, scaleOrientation) and the other grouping
// nodes' children (Group, Anchor, Billboard, Collision; LOD's first level;
// Switch's whichChoice), Shape with Appearance/Material diffuseColor and
// IndexedFaceSet geometry (Coordinate point, coordIndex with -1-separated
// polygons fan-triangulated; ccw FALSE flips them; other fields are skipped).
// Other geometry (Box, IndexedLineSet, ...) and ROUTEs are skipped; PROTO is refused.
//
// One Mesh per Shape instance (a USE'd Shape or Transform gives one per use),
// transforms applied, metres (VRML's unit) to millimetres (x 1000). Names: the
// nearest DEF (the Shape's, else the closest enclosing node's), else the file's
// stem; repeats are numbered (_2, _3). mesh.color is the diffuseColor (the VRML
// default 0.8 grey when the Shape has no Material). Normals are not read.
// Errors (exit 2): one line "PATH:LINE: reason" (bad header, syntax, nesting
// deeper than 64, an index out of range, an unterminated node, no triangles).
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/mesh.h"

namespace body {

Result<std::vector<Mesh>> read_vrml(const std::string& path);

}  // namespace body
