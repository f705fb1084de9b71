// Triangle ids as colours: 0xFFFFFFFF is "no triangle"; ids use the low 31 bits.
#include "ui/render/triangle_ids.h"

#include "core/engine/mesh.h"

namespace dlab::ui {

namespace {
constexpr std::uint32_t kNoTriangle = 0xFFFFFFFFu;
}

std::array<std::uint8_t, 4> encodeTriangleId(std::int32_t id) {
    const std::uint32_t v = id < 0 ? kNoTriangle : static_cast<std::uint32_t>(id);
    return {static_cast<std::uint8_t>((v >> 16) & 255), static_cast<std::uint8_t>((v >> 8) & 255),
            static_cast<std::uint8_t>(v & 255), static_cast<std::uint8_t>((v >> 24) & 255)};
}

std::int32_t decodeTriangleId(const std::uint8_t* c) {
    const std::uint32_t v = (std::uint32_t{c[3]} << 24) | (std::uint32_t{c[0]} << 16) |
                            (std::uint32_t{c[1]} << 8) | c[2];
    return v == kNoTriangle ? kNone : static_cast<std::int32_t>(v & 0x7FFFFFFFu);
}

}  // namespace dlab::ui
