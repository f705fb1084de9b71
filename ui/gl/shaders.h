// The shaders of every GL program we draw with, written once in the common subset of GLSL 3.30
// core and GLSL ES 3.00 (the #version line comes from gl_api.h, per target), and the list that
// the tests compile in both languages.
#pragma once

namespace dlab::ui::shaders {

// ---- The mesh renderer (mesh_renderer.cpp) ----------------------------------------------------

// Shapes: 0 triangles (aPoint per vertex), 1 segments and 2 squares (one instance each: six
// vertices spanning a quad around aSegment or aPoint). Positions are display pixels, y down, as
// ImGui's. (The dense raster is drawn by ImGui, as an image.)
inline constexpr const char* kMeshVertexShader = R"(
layout(location = 0) in vec2 aPoint;
layout(location = 1) in vec4 aSegment;
uniform int uShape;
uniform vec4 uScreen;  // the display: left, top, width, height
uniform float uSize;   // segment width, square side
const vec2 kCorner[6] = vec2[6](vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(1.0, 1.0),
                                vec2(0.0, 0.0), vec2(1.0, 1.0), vec2(0.0, 1.0));
void main() {
    vec2 q = kCorner[gl_VertexID % 6];
    vec2 p;
    if (uShape == 0) {
        p = aPoint;
    } else if (uShape == 1) {
        vec2 d = aSegment.zw - aSegment.xy;
        float len = length(d);
        vec2 u = len > 0.0 ? d / len : vec2(1.0, 0.0);
        vec2 n = vec2(-u.y, u.x);
        vec2 cap = 0.5 * uSize * u;  // square caps: joints stay closed at any width
        p = mix(aSegment.xy - cap, aSegment.zw + cap, q.x) + (q.y - 0.5) * uSize * n;
    } else {
        p = aPoint + (q - 0.5) * uSize;
    }
    gl_Position = vec4((p.x - uScreen.x) / uScreen.z * 2.0 - 1.0,
                       1.0 - (p.y - uScreen.y) / uScreen.w * 2.0, 0.0, 1.0);
}
)";

inline constexpr const char* kMeshFragmentShader = R"(
uniform vec4 uColour;
out vec4 fragColour;
void main() {
    fragColour = uColour;
}
)";

// ---- The GL colour-ID buffer (idbuffer_gl.cpp) ------------------------------------------------

// Painting: each triangle in its id's colour, flat (the three vertices carry the same bytes, and
// no interpolation may round them), at pixel coordinates with y up.
inline constexpr const char* kPaintVertexShader = R"(
layout(location = 0) in vec2 aPixel;
layout(location = 1) in vec4 aColour;
uniform vec2 uTarget;
flat out vec4 vColour;
void main() {
    vColour = aColour;
    gl_Position = vec4(aPixel / uTarget * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Gathering: point k of a batch goes to pixel (k % width, k / width) of the gather target and
// carries the ID texture's texel under its point, fetched by integer address (exact).
inline constexpr const char* kGatherVertexShader = R"(
layout(location = 0) in ivec2 aTexel;
uniform sampler2D uIds;
uniform ivec2 uTarget;
flat out vec4 vColour;
void main() {
    vColour = texelFetch(uIds, aTexel, 0);
    vec2 cell = vec2(float(gl_VertexID % uTarget.x), float(gl_VertexID / uTarget.x));
    gl_Position = vec4((cell + 0.5) / vec2(uTarget) * 2.0 - 1.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
)";

inline constexpr const char* kFlatFragmentShader = R"(
flat in vec4 vColour;
out vec4 fragColour;
void main() {
    fragColour = vColour;
}
)";

struct Program {
    const char* name;
    const char* vertex;
    const char* fragment;
};
inline constexpr Program kPrograms[] = {
    {"mesh", kMeshVertexShader, kMeshFragmentShader},
    {"id paint", kPaintVertexShader, kFlatFragmentShader},
    {"id gather", kGatherVertexShader, kFlatFragmentShader},
};

}  // namespace dlab::ui::shaders
