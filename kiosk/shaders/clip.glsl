// The cut plane (kiosk/render/cut_plane.h) in every fragment stage: GLES 3.0
// has no gl_ClipDistance, so fragments on the removed side are discarded. Only
// the clipped program variants define BODY_CLIP (styles/cut_cap.cpp links them
// at the first cut), since a discard costs early depth testing on many GPUs.
// No varying: the view position comes from gl_FragCoord and its depth,
// view z = -B / (ndc z + A) with A = P[2][2], B = P[3][2] of the perspective.
#if defined(BODY_CLIP) && !defined(BODY_CLIP_DISTANCE)  // else clip_vertex.glsl clips
uniform highp vec4 u_clip_plane;  // view space; removed where dot(xyz, p) + w > 0
uniform highp vec4 u_clip_ray;    // gl_FragCoord.xy -> view ray at z = -1 (as u_view_ray)
uniform highp vec2 u_clip_depth;  // A, B
void clip_fragment() {
    highp float depth = u_clip_depth.y / (2.0 * gl_FragCoord.z - 1.0 + u_clip_depth.x);  // -view z
    highp vec3 p = vec3(gl_FragCoord.xy * u_clip_ray.xy + u_clip_ray.zw, -1.0) * depth;
    if (dot(u_clip_plane.xyz, p) + u_clip_plane.w > 0.0) discard;
}
#else
void clip_fragment() {}
#endif
