# The browser build's third-party code (make web; included by the top-level CMakeLists.txt when
# the compiler is Emscripten's). Debian's header-only packages (nlohmann-json, toml++, glm,
# fast_float, {fmt}, stb) are reached through a folder of links of their own, never through all
# of /usr/include (whose C library headers are not Emscripten's). Dear ImGui and giflib are
# compiled from the sources of Debian's packages (.ci/debian_source.sh; the versions of
# libimgui-dev and libgif-dev). The targets carry the names find_package gives natively, so
# core/, ui/ and app/ link them the same way.
# The code reports bad input by exceptions (core/engine/io_read.h): Emscripten's default build
# would abort on the first throw instead of catching it.
add_compile_options(-fexceptions)
add_link_options(-fexceptions)

set(DLAB_WEB_DEPS_DIR "${CMAKE_BINARY_DIR}/_deps" CACHE PATH "Where the browser build's sources are unpacked")
foreach(pkg IN ITEMS "imgui;libimgui-dev;IMGUI" "giflib;libgif-dev;GIFLIB")
  list(GET pkg 0 source)
  list(GET pkg 1 binary)
  list(GET pkg 2 var)
  if(NOT DLAB_${var}_SOURCE_DIR)
    execute_process(
      COMMAND bash "${PROJECT_SOURCE_DIR}/.ci/debian_source.sh" "${DLAB_WEB_DEPS_DIR}" ${source} ${binary}
      OUTPUT_VARIABLE dir OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "the sources of ${source} (Debian's, as ${binary}) are needed for the browser build")
    endif()
    set(DLAB_${var}_SOURCE_DIR "${dir}")  # not cached: checked (fast) at every configure
  endif()
endforeach()

set(DLAB_WEB_INCLUDE "${CMAKE_BINARY_DIR}/debian-include")
file(MAKE_DIRECTORY "${DLAB_WEB_INCLUDE}")
foreach(dir IN ITEMS nlohmann toml++ glm fast_float fmt)
  if(NOT EXISTS "/usr/include/${dir}")
    message(FATAL_ERROR "/usr/include/${dir} not found: the browser build uses Debian's headers "
                        "(make web installs them)")
  endif()
  file(CREATE_LINK "/usr/include/${dir}" "${DLAB_WEB_INCLUDE}/${dir}" SYMBOLIC)
endforeach()

add_library(dlab_web_headers INTERFACE)
target_include_directories(dlab_web_headers SYSTEM INTERFACE "${DLAB_WEB_INCLUDE}")
foreach(name IN ITEMS nlohmann_json::nlohmann_json tomlplusplus::tomlplusplus glm::glm
                      FastFloat::fast_float fmt::fmt-header-only)
  add_library(${name} ALIAS dlab_web_headers)
endforeach()
target_compile_definitions(dlab_web_headers INTERFACE FMT_HEADER_ONLY=1)

# Dear ImGui with the C++ std::string helpers, the GLFW backend (Emscripten's GLFW on the canvas)
# and stb_image_write (PNG screenshots); ui/ compiles the OpenGL3 backend itself.
set(imgui "${DLAB_IMGUI_SOURCE_DIR}")
add_library(dlab_web_imgui STATIC
  ${imgui}/imgui.cpp ${imgui}/imgui_draw.cpp ${imgui}/imgui_tables.cpp ${imgui}/imgui_widgets.cpp
  ${imgui}/misc/cpp/imgui_stdlib.cpp ${imgui}/backends/imgui_impl_glfw.cpp
  ${PROJECT_SOURCE_DIR}/ui/platform/platform_web_stb.cpp)
target_include_directories(dlab_web_imgui SYSTEM PUBLIC ${imgui} ${imgui}/misc/cpp ${imgui}/backends
                           /usr/include/stb)
target_compile_options(dlab_web_imgui PRIVATE -w)
add_library(PkgConfig::IMGUI ALIAS dlab_web_imgui)

set(gif "${DLAB_GIFLIB_SOURCE_DIR}")
add_library(dlab_web_gif STATIC ${gif}/dgif_lib.c ${gif}/egif_lib.c ${gif}/gifalloc.c
            ${gif}/gif_err.c ${gif}/gif_hash.c ${gif}/openbsd-reallocarray.c ${gif}/quantize.c)
target_include_directories(dlab_web_gif SYSTEM PUBLIC ${gif})
target_compile_options(dlab_web_gif PRIVATE -w)
add_library(GIF::GIF ALIAS dlab_web_gif)

