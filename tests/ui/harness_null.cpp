// The logic tests' platform: no GL at all; the null renderer draws nothing.
#include "tests/ui/ui_harness.h"

namespace dlab::test {

std::unique_ptr<ui::Platform> makeTestPlatform(int width, int height, std::string&) {
    return ui::makeNullPlatform(width, height);
}

}  // namespace dlab::test
