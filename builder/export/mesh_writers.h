#pragma once
// Formats without groups or a scene graph: every model's placement is applied
// to its vertices (scene millimetres kept). Each file is written atomically.
//
// - STL, binary: all models' triangles, facet normals from the placed
//   vertices, the colour in each facet's attribute word (VisCAM/SolidView:
//   bit 15 set, 5 bits each of blue, green, red). STL keeps no names.
// - PLY, binary little-endian: one vertex list (x y z float, nx ny nz float
//   when every model has normals, red green blue uchar) and one face list
//   (uchar count, int indices); `comment model NAME first_vertex count` header
//   lines say which vertices are which model.
// - VRML97 (.wrl): one `DEF <name> Transform` per model (names made VRML
//   identifiers) inside a `DEF <group> Transform` per group, each with a Shape:
//   Material diffuseColor = the colour, IndexedFaceSet (ccw, solid, per-vertex
//   normals when present), under a root Transform scaling millimetres to metres.
// - OBJ: one object per model (shared/obj_io.h).
#include <string>

#include "builder/export/export_scene.h"
#include "shared/error.h"

namespace body::exporter {

Status write_stl(const std::string& path, const ExportScene& scene);
Status write_ply(const std::string& path, const ExportScene& scene);
Status write_vrml(const std::string& path, const ExportScene& scene);
Status write_placed_obj(const std::string& path, const ExportScene& scene);

// A VRML97 identifier from a name: characters VRML forbids become '_', a
// leading digit or sign gets a '_' before it.
std::string vrml_identifier(const std::string& name);

}  // namespace body::exporter
