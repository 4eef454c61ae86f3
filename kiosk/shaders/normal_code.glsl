// The one normal code: 8:8 octahedral (Meyer et al. 2010), unsigned, decoded
// exactly as pm::oct_decode8 (shared/pm/quantize.cpp) does.
vec3 oct_decode8(vec2 code) {
    vec2 e = code * (2.0 / 255.0) - 1.0;
    float z = 1.0 - abs(e.x) - abs(e.y);
    float t = max(-z, 0.0);  // folding the lower hemisphere back
    e += mix(vec2(t), vec2(-t), greaterThanEqual(e, vec2(0.0)));
    return normalize(vec3(e, z));
}
