// The paper's colour encoding of triangle ids (RGBA bytes in memory order), shared by the GL ID
// buffer and the ID-buffer view; no GL here.
#pragma once

#include <array>
#include <cstdint>

namespace dlab::ui {

std::array<std::uint8_t, 4> encodeTriangleId(std::int32_t id);  // kNone -> the "no triangle" colour
std::int32_t decodeTriangleId(const std::uint8_t* rgba);        // the "no triangle" colour -> kNone

}  // namespace dlab::ui
