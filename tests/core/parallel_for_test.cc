// Jobs run side by side: ParallelForEachCatching runs every job to its end whatever the others
// throw and says which threw; RethrowFirst reports the first by index.

#include "engine/core/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

namespace recon {
namespace {

std::string MessageOf(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(ParallelForTest, EveryJobRunsToItsEndAndEachFailureIsKeptByIndex) {
  for (const unsigned threads : {1u, 2u, 4u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    std::vector<std::atomic<int>> ran(6);
    const std::vector<std::exception_ptr> errors =
        ParallelForEachCatching(ran.size(), threads, [&](size_t i) {
          ++ran[i];
          if (i == 1 || i == 4) throw std::runtime_error("job " + std::to_string(i));
        });
    ASSERT_EQ(errors.size(), ran.size());
    for (size_t i = 0; i < ran.size(); ++i) {
      EXPECT_EQ(ran[i], 1) << "job " << i;
      EXPECT_EQ(errors[i] != nullptr, i == 1 || i == 4) << "job " << i;
    }
    EXPECT_EQ(MessageOf(errors[4]), "job 4");
    try {
      RethrowFirst(errors);
      ADD_FAILURE() << "nothing rethrown";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "job 1");
    }
  }
  EXPECT_NO_THROW(RethrowFirst(std::vector<std::exception_ptr>(3)));
  EXPECT_TRUE(ParallelForEachCatching(0, 2, [](size_t) {}).empty());
}

}  // namespace
}  // namespace recon
