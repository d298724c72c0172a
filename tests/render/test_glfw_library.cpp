// GLFW is loaded when the first window is opened (glfw_library.hpp): a missing library or one
// without GLFW's entry points is refused with a message naming it and the Debian package, and
// the real one resolves every entry point.
#include <gtest/gtest.h>

#include <string>

#include "sutura/render/context.hpp"
#include "sutura/render/glfw_library.hpp"

using sutura::render::GlError;

TEST(RenderGlfw, AMissingLibraryIsNamedWithItsPackage) {
  try {
    (void)sutura::render::load_glfw("libglfw-not-here.so.3");
    ADD_FAILURE() << "a missing library loaded";
  } catch (const GlError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("libglfw-not-here.so.3"), std::string::npos) << m;
    EXPECT_NE(m.find("libglfw3"), std::string::npos) << m;
  }
  // libm has none of GLFW's entry points: refused by the first one's name.
  try {
    (void)sutura::render::load_glfw("libm.so.6");
    ADD_FAILURE() << "libm was taken for GLFW";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("glfwInit"), std::string::npos) << e.what();
  }
}

TEST(RenderGlfw, TheInstalledLibraryResolvesEveryEntryPoint) {
  const sutura::render::GlfwLibrary& g = sutura::render::glfw();
  EXPECT_EQ(&g, &sutura::render::glfw());  // loaded once
  for (const void* fn : {reinterpret_cast<const void*>(g.init), reinterpret_cast<const void*>(g.create_window),
                         reinterpret_cast<const void*>(g.get_proc_address),
                         reinterpret_cast<const void*>(g.set_scroll_callback)})
    EXPECT_NE(fn, nullptr);
}
