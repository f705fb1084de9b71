// The browser build compiles stb_image_write itself (natively it comes from Debian's libstb).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
