/**
 * @file
 * Helpers shared by the unit tests that write input files or expect input
 * errors: a fresh scratch folder, a file writer, and the message of the
 * InputError a call throws.
 */
#ifndef ROCKDDA_TESTS_TEST_FILES_H
#define ROCKDDA_TESTS_TEST_FILES_H

#include <rockdda/io/error.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace rockdda::test_files
{
  /// The scratch folders of this process, removed when the test program
  /// exits (a test that fails keeps its folder only until then).
  struct ScratchFolders
  {
    std::vector<std::filesystem::path> paths;

    ~ScratchFolders()
    {
      for (const auto &p : paths)
        {
          std::error_code ignored;
          std::filesystem::remove_all(p, ignored);
        }
    }
  };

  /// A fresh, empty temporary folder for one test (unique per process),
  /// removed at exit.
  inline std::filesystem::path
  scratch(const std::string &name)
  {
    static ScratchFolders       folders;
    const std::filesystem::path p
      = std::filesystem::temp_directory_path()
        / ("rockdda-test-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    folders.paths.push_back(p);
    return p;
  }

  /// Write @p text to the file @p p.
  inline void
  write_file(const std::filesystem::path &p, const std::string &text)
  {
    std::ofstream(p) << text;
  }

  /// The message of the InputError that @p f() throws ("" if none).
  template <typename F>
  std::string
  error_of(F &&f)
  {
    try
      {
        f();
      }
    catch (const InputError &e)
      {
        return e.what();
      }
    return "";
  }
} // namespace rockdda::test_files

#endif
