// The GL layer on the headless core-profile context (OSMesa, or EGL on llvmpipe): the context it
// asks for, and every shader program built in both shader languages we ship to (GLSL 3.30 core
// here and in the window, GLSL ES 3.00 in the browser: desktop GL 4.3 and later compile it too).
#include "tests/ui/ui_harness.h"
#include "ui/gl/gl_api.h"
#include "ui/gl/shaders.h"

#include <gtest/gtest.h>

#include <string>

using namespace dlab;

namespace {

class GlTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(m_headless.open(error)) << error;
    }
    test::HeadlessGl m_headless;
};

}  // namespace

TEST_F(GlTest, TheHeadlessContextIsACoreProfile) {
    GLint mask = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    EXPECT_TRUE(mask & GL_CONTEXT_CORE_PROFILE_BIT) << m_headless.gl->version();
    // Fixed-function calls do not exist there: the one renderer cannot lean on them.
    glGetError();
    glEnable(0x0B50);  // GL_LIGHTING, compatibility only
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
}

TEST_F(GlTest, EveryProgramBuildsAsGlsl330CoreAndAsGlslEs300) {
    for (const auto& p : ui::shaders::kPrograms) {
        for (const char* preamble : {ui::kGlslCorePreamble, ui::kGlslEsPreamble}) {
            std::string error;
            const GLuint program = ui::buildProgram(p.vertex, p.fragment, error, preamble);
            EXPECT_NE(program, 0u) << p.name << " with " << preamble << error;
            glDeleteProgram(program);
        }
    }
}

TEST_F(GlTest, ABrokenShaderIsRefusedWithTheCompilersLog) {
    std::string error;
    const GLuint program = ui::buildProgram("void main() { gl_Position = vec4(1.0); }\n",
                                            "out vec4 c;\nvoid main() { c = nope; }\n", error);
    EXPECT_EQ(program, 0u);
    EXPECT_NE(error.find("fragment shader"), std::string::npos) << error;
    EXPECT_NE(error.find("nope"), std::string::npos) << error;
}
