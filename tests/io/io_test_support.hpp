#pragma once
// Helpers shared by the io tests: a self-deleting temporary directory and a check that a call
// throws InputError whose message contains given fragments.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <unistd.h>

#include "imunoise/error.hpp"

namespace imunoise::test {

/// A fresh directory under the system temp dir, removed with its contents on destruction.
class TempDir {
 public:
  TempDir() {
    static std::atomic<unsigned> counter{0};
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = std::filesystem::temp_directory_path() /
            ("imunoise_io_test_" + std::to_string(::getpid()) + "_" + std::to_string(stamp) +
             "_" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

  /// Writes `bytes` verbatim (binary mode) to a file in the directory and returns its path.
  std::filesystem::path write(const std::string& name, std::string_view bytes) const {
    const auto file = path_ / name;
    std::ofstream out(file, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return file;
  }

 private:
  std::filesystem::path path_;
};

/// Runs `call`, expects an InputError, and checks that its message contains every fragment and
/// the word "fix:" (every message must say how to fix the input). Returns the message.
inline std::string expect_input_error(const std::function<void()>& call,
                                      std::initializer_list<std::string_view> fragments) {
  try {
    call();
  } catch (const InputError& error) {
    const std::string message = error.what();
    for (std::string_view fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message lacks \"" << fragment << "\":\n  " << message;
    }
    EXPECT_NE(message.find("fix:"), std::string::npos) << "message lacks a fix:\n  " << message;
    return message;
  } catch (const std::exception& other) {
    ADD_FAILURE() << "expected InputError, got another exception: " << other.what();
    return {};
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return {};
}

}  // namespace imunoise::test
