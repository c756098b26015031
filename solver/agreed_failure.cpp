// Agreed failures (agreed_failure.hpp): the failing processes' kinds gathered, the lowest one's
// message broadcast, the same exception rebuilt everywhere.
#include "solver/agreed_failure.hpp"

#include <cstdint>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>

#include "common/input_error.hpp"

namespace mppm::solver {

namespace {

enum class FailureKind : std::int64_t { none, bad_input, numerical, out_of_memory, other };

// The exceptions run_agreed rebuilt: failure_was_agreed knows them by their type.
struct AgreedInputError : InputError {
  using InputError::InputError;
};
struct AgreedNumericalFailure : NumericalFailure {
  using NumericalFailure::NumericalFailure;
};
struct AgreedOutOfMemory : std::bad_alloc {};
struct AgreedOtherFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

FailureKind kind_of(const std::exception_ptr& failure, std::string& message) {
  try {
    std::rethrow_exception(failure);
  } catch (const InputError& e) {
    message = e.what();
    return FailureKind::bad_input;
  } catch (const NumericalFailure& e) {
    message = e.what();
    return FailureKind::numerical;
  } catch (const std::bad_alloc&) {
    return FailureKind::out_of_memory;
  } catch (const std::exception& e) {
    message = e.what();
    return FailureKind::other;
  } catch (...) {
    message = "an unknown exception";
    return FailureKind::other;
  }
}

[[noreturn]] void throw_agreed(FailureKind kind, const std::string& message) {
  switch (kind) {
    case FailureKind::bad_input:
      throw AgreedInputError(message);
    case FailureKind::numerical:
      throw AgreedNumericalFailure(message);
    case FailureKind::out_of_memory:
      throw AgreedOutOfMemory();
    default:
      throw AgreedOtherFailure(message);
  }
}

}  // namespace

void run_agreed(const ProcessGroup& group, const std::function<void()>& step) {
  if (!group.distributed()) {
    step();
    return;
  }
  std::exception_ptr failure;
  try {
    step();
  } catch (...) {
    failure = std::current_exception();
  }
  constexpr std::int64_t kNobody = std::numeric_limits<std::int64_t>::max();
  const std::int64_t first = group.lowest(failure ? group.rank() : kNobody);
  if (first == kNobody) return;
  std::string message;
  const FailureKind mine = failure ? kind_of(failure, message) : FailureKind::none;
  const auto root = static_cast<int>(first);
  const auto kind = static_cast<FailureKind>(group.gather(static_cast<std::int64_t>(mine))[first]);
  throw_agreed(kind, group.broadcast(message, root));
}

bool failure_was_agreed(const std::exception_ptr& failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const AgreedInputError&) {
    return true;
  } catch (const AgreedNumericalFailure&) {
    return true;
  } catch (const AgreedOutOfMemory&) {
    return true;
  } catch (const AgreedOtherFailure&) {
    return true;
  } catch (...) {
    return false;
  }
}

}  // namespace mppm::solver
