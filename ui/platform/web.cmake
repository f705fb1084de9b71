# The browser build of the GUI (make web): dlab_ui as natively, its one platform (WebGL2 through
# Emscripten's GLFW on the page's canvas: platform_web.cpp) and the page (index.html with
# platform_web.js). Included by ui/CMakeLists.txt when the compiler is Emscripten's; the
# third-party targets come from web_packages.cmake. Output: the build folder holds index.html,
# delaunay-lab.js, delaunay-lab.wasm and delaunay-lab.data (lessons, their point sets, fonts).
file(GLOB DLAB_UI_SOURCES CONFIGURE_DEPENDS
     ${PROJECT_SOURCE_DIR}/ui/*.cpp
     ${PROJECT_SOURCE_DIR}/ui/panels/*.cpp
     ${PROJECT_SOURCE_DIR}/ui/render/*.cpp
     ${PROJECT_SOURCE_DIR}/ui/files/*.cpp)
add_library(dlab_ui STATIC ${DLAB_UI_SOURCES})
add_library(dlab::ui ALIAS dlab_ui)
target_include_directories(dlab_ui PUBLIC ${PROJECT_SOURCE_DIR})
target_compile_definitions(dlab_ui PRIVATE DLAB_LESSONS_DIR="/lessons")  # bundled (below)
target_link_libraries(dlab_ui PUBLIC dlab::engine dlab::teaching PkgConfig::IMGUI glm::glm)
target_link_libraries(dlab_ui PRIVATE GIF::GIF nlohmann_json::nlohmann_json)

file(GLOB DLAB_UI_GL_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/ui/gl/*.cpp)
add_library(dlab_ui_gl STATIC ${DLAB_UI_GL_SOURCES})
add_library(dlab::ui_gl ALIAS dlab_ui_gl)
target_link_libraries(dlab_ui_gl PUBLIC dlab::ui)
set_source_files_properties(${PROJECT_SOURCE_DIR}/ui/gl/imgui_backend.cpp PROPERTIES
  COMPILE_DEFINITIONS "DLAB_IMGUI_OPENGL3_SOURCE=\"${DLAB_IMGUI_SOURCE_DIR}/backends/imgui_impl_opengl3.cpp\""
  COMPILE_OPTIONS "-w")

set(DLAB_WEB_LINK_OPTIONS -sUSE_GLFW=3 -sMIN_WEBGL_VERSION=2 -sMAX_WEBGL_VERSION=2)
add_library(dlab_platform_web STATIC platform/platform_web.cpp)
add_library(dlab::platform_web ALIAS dlab_platform_web)
target_link_libraries(dlab_platform_web PUBLIC dlab::ui_gl)
target_link_options(dlab_platform_web PUBLIC ${DLAB_WEB_LINK_OPTIONS})

# The page: the GUI on a canvas that fills the window, the file picker, downloads, IndexedDB,
# URL parameters, touch, Table 1, and the hooks the browser test drives.
set(fonts /usr/share/fonts/truetype/dejavu)
foreach(font DejaVuSans.ttf DejaVuSansMono.ttf DejaVuSans-Bold.ttf)
  if(EXISTS ${fonts}/${font})
    list(APPEND DLAB_WEB_BUNDLE "--preload-file=${fonts}/${font}@${fonts}/${font}")
  endif()
endforeach()
add_executable(delaunay-lab ${PROJECT_SOURCE_DIR}/app/delaunay_lab_web.cpp)
target_link_libraries(delaunay-lab PRIVATE dlab::platform_web)
target_link_options(delaunay-lab PRIVATE
  -sALLOW_MEMORY_GROWTH=1 -sINITIAL_MEMORY=67108864 -sMAXIMUM_MEMORY=2147483648
  -sFORCE_FILESYSTEM=1 -lidbfs.js -sEXIT_RUNTIME=0
  "-sEXPORTED_FUNCTIONS=_main,_malloc,_free" "-sEXPORTED_RUNTIME_METHODS=ccall,cwrap,FS,UTF8ToString"
  "--preload-file=${PROJECT_SOURCE_DIR}/lessons@/lessons" ${DLAB_WEB_BUNDLE})
set_target_properties(delaunay-lab PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR} SUFFIX ".js")
file(GLOB DLAB_WEB_LESSON_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/lessons/*
     ${PROJECT_SOURCE_DIR}/lessons/points/*)
set_property(TARGET delaunay-lab APPEND PROPERTY LINK_DEPENDS ${DLAB_WEB_LESSON_FILES})
foreach(page index.html platform_web.js)
  set(src ${CMAKE_CURRENT_SOURCE_DIR}/platform/${page})
  if(page STREQUAL "index.html")
    set(src ${CMAKE_CURRENT_SOURCE_DIR}/platform/platform_web.html)
  endif()
  add_custom_command(OUTPUT ${CMAKE_BINARY_DIR}/${page} COMMAND ${CMAKE_COMMAND} -E copy ${src}
                     ${CMAKE_BINARY_DIR}/${page} DEPENDS ${src} VERBATIM)
  list(APPEND DLAB_WEB_PAGES ${CMAKE_BINARY_DIR}/${page})
endforeach()
add_custom_target(web-page ALL DEPENDS ${DLAB_WEB_PAGES})
add_dependencies(delaunay-lab web-page)
