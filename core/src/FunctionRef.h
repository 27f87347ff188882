#pragma once

// A non-owning reference to a callable: std::function without the allocation, for the
// thread pool's per-render dispatch (re-rendering must not allocate).

#include <memory>
#include <type_traits>
#include <utility>

namespace facet::detail {

template <class Signature>
class FunctionRef;

template <class R, class... Args>
class FunctionRef<R(Args...)> {
 public:
  FunctionRef() = default;
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, FunctionRef>>>
  FunctionRef(F& callable)  // NOLINT(google-explicit-constructor): used like std::function
      : object_(std::addressof(callable)), invoke_([](void* object, Args... args) -> R {
          return (*static_cast<F*>(object))(std::forward<Args>(args)...);
        }) {}

  explicit operator bool() const { return invoke_ != nullptr; }
  R operator()(Args... args) const { return invoke_(object_, std::forward<Args>(args)...); }

 private:
  void* object_ = nullptr;
  R (*invoke_)(void*, Args...) = nullptr;
};

}  // namespace facet::detail
