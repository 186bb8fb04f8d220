#include "interruption.hpp"

namespace swarmcollide {

namespace {

thread_local detail::InterruptionHook installed;

}  // namespace

const char* Interrupted::what() const noexcept { return "interrupted"; }

InterruptionGuard::InterruptionGuard(InterruptionCheck check, void* context) noexcept
    : previous_check_(installed.check), previous_context_(installed.context) {
  installed = {check, context};
}

InterruptionGuard::~InterruptionGuard() { installed = {previous_check_, previous_context_}; }

namespace detail {

InterruptionHook current_interruption_hook() noexcept { return installed; }

}  // namespace detail

}  // namespace swarmcollide
