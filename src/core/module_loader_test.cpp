// The plugin loader's search path and its error for a missing module (the plugins themselves
// are exercised by the image, grid and mesh tests, and by cli_test).
#include "core/module_loader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

namespace caligo {
namespace {

TEST(ModuleLoader, SearchesTheExecutablesFolderFirst) {
  const std::string exe_dir = std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
  EXPECT_EQ(module_search_path().rfind(exe_dir, 0), 0u) << module_search_path();
}

TEST(ModuleLoader, AMissingModuleNamesItselfItsPurposeAndWhereItLooked) {
  try {
    module_symbol("caligo_no_such_plugin", "entry", "needed for nothing");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("caligo_no_such_plugin.so"), std::string::npos) << what;
    EXPECT_NE(what.find("needed for nothing"), std::string::npos) << what;
    EXPECT_NE(what.find(std::filesystem::read_symlink("/proc/self/exe").parent_path().string()), std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace caligo
