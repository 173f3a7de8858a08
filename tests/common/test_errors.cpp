// Tests of common/errors.hpp: the error tiers are distinct types and current_error_text gives the
// message of the exception being handled.
#include "common/errors.hpp"

#include <gtest/gtest.h>

#include <string>
#include <type_traits>

namespace {

template <class E>
std::string text_of(const E& e) {
  try {
    throw e;
  } catch (...) {
    return common::current_error_text();
  }
}

}  // namespace

TEST(Errors, CurrentErrorText) {
  EXPECT_EQ(text_of(common::InputError("job.toml:3: bad")), "job.toml:3: bad");
  EXPECT_EQ(text_of(common::IoError("cannot fsync 'a': EIO")), "cannot fsync 'a': EIO");
  EXPECT_EQ(text_of(42), "unknown exception");
}

TEST(Errors, IoErrorIsNeitherInputNorInternal) {
  static_assert(!std::is_base_of_v<common::InputError, common::IoError>);
  static_assert(!std::is_base_of_v<common::InternalError, common::IoError>);
  EXPECT_THROW(throw common::IoError("x"), std::runtime_error);
}
