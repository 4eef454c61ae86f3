// The cut plane (kiosk/render/cut_plane.h) in the vertex stages, where the
// driver offers GL_EXT_clip_cull_distance (styles/cut_cap.cpp links that
// variant, BODY_CLIP_DISTANCE): the removed side is clipped off as geometry,
// so none of its fragments is shaded and clip.glsl's discard, which costs
// early depth testing, is left out. Otherwise both functions do nothing.
#ifdef BODY_CLIP_DISTANCE
uniform highp vec4 u_clip_object;  // object space; removed where dot(xyz, p) + w > 0
float clip_distance(vec3 p) { return -(dot(u_clip_object.xyz, p) + u_clip_object.w); }
void clip_vertex(float distance) { gl_ClipDistance[0] = distance; }
#else
float clip_distance(vec3 p) { return 0.0; }
void clip_vertex(float distance) {}
#endif
