// A move-only type-erased callable with a small inline buffer, so that event
// callbacks (a lambda capturing a few pointers) never touch the heap.
#pragma once

#include <cstddef>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>

namespace latsim::des {

template <class Signature, std::size_t InlineBytes = 32>
class InlineFunction;

/// Holds any callable R(Args...): inline when it fits in InlineBytes and is
/// nothrow-movable, on the heap otherwise.
///
/// Callables that are trivially copyable and destructible (the common lambda
/// capturing pointers and integers) need no manager at all: moving one is a
/// memcpy and destroying it is a no-op, which keeps the event loop free of
/// indirect calls other than the invocation itself.
template <class R, class... Args, std::size_t InlineBytes>
class InlineFunction<R(Args...), InlineBytes> {
 public:
  static constexpr std::size_t kInlineBytes = InlineBytes;

  /// True when a callable of type F is stored without a heap allocation.
  template <class F>
  static constexpr bool stores_inline =
      sizeof(F) <= InlineBytes && alignof(F) <= alignof(std::max_align_t) &&
      std::is_nothrow_move_constructible_v<F>;

  InlineFunction() noexcept = default;

  template <class F, class D = std::decay_t<F>,
            class = std::enable_if_t<!std::is_same_v<D, InlineFunction> && std::is_invocable_r_v<R, D&, Args...>>>
  InlineFunction(F&& f) {  // NOLINT(google-explicit-constructor): converting like std::function
    emplace<D>(std::forward<F>(f));
  }

  InlineFunction(InlineFunction&& o) noexcept { take(o); }
  InlineFunction& operator=(InlineFunction&& o) noexcept {
    if (this != &o) {
      reset();
      take(o);
    }
    return *this;
  }
  InlineFunction(const InlineFunction&) = delete;
  InlineFunction& operator=(const InlineFunction&) = delete;
  ~InlineFunction() { reset(); }

  explicit operator bool() const noexcept { return invoke_ != nullptr; }

  R operator()(Args... args) { return invoke_(buffer_, std::forward<Args>(args)...); }

  /// Replaces the held callable with f, constructed in place.
  template <class F>
  void assign(F&& f) {
    reset();
    emplace<std::decay_t<F>>(std::forward<F>(f));
  }

  /// Constructs f in place; this must be empty (cheaper than assign()).
  template <class F>
  void construct(F&& f) {
    emplace<std::decay_t<F>>(std::forward<F>(f));
  }

  /// Destroys the held callable (and whatever it captured); leaves this empty.
  void reset() noexcept {
    if (manage_ != nullptr) manage_(Op::destroy, buffer_, nullptr);
    invoke_ = nullptr;
    manage_ = nullptr;
  }

 private:
  enum class Op { move_to, destroy };
  using Invoke = R (*)(void*, Args&&...);
  using Manage = void (*)(Op, void* self, void* dest);

  template <class D, class F>
  void emplace(F&& f) {
    if constexpr (stores_inline<D>) {
      ::new (static_cast<void*>(buffer_)) D(std::forward<F>(f));
      invoke_ = [](void* b, Args&&... a) -> R { return (*std::launder(static_cast<D*>(b)))(std::forward<Args>(a)...); };
      if constexpr (std::is_trivially_copyable_v<D> && std::is_trivially_destructible_v<D>) {
        manage_ = nullptr;  // memcpy moves it, nothing to destroy
      } else {
        manage_ = [](Op op, void* self, void* dest) {
          D* obj = std::launder(static_cast<D*>(self));
          if (op == Op::move_to) ::new (dest) D(std::move(*obj));
          obj->~D();
        };
      }
    } else {
      // Too big or throwing on move: keep it on the heap and store the pointer inline.
      D* heap = new D(std::forward<F>(f));
      std::memcpy(buffer_, &heap, sizeof heap);
      invoke_ = [](void* b, Args&&... a) -> R {
        D* p = nullptr;
        std::memcpy(&p, b, sizeof p);
        return (*p)(std::forward<Args>(a)...);
      };
      manage_ = [](Op op, void* self, void* dest) {
        if (op == Op::move_to) {
          std::memcpy(dest, self, sizeof(D*));
        } else {
          D* p = nullptr;
          std::memcpy(&p, self, sizeof p);
          delete p;
        }
      };
    }
  }

  void take(InlineFunction& o) noexcept {
    invoke_ = o.invoke_;
    manage_ = o.manage_;
    if (manage_ != nullptr) {
      manage_(Op::move_to, o.buffer_, buffer_);
    } else if (invoke_ != nullptr) {
      std::memcpy(buffer_, o.buffer_, InlineBytes);
    }
    o.invoke_ = nullptr;
    o.manage_ = nullptr;
  }

  Invoke invoke_ = nullptr;
  Manage manage_ = nullptr;
  alignas(std::max_align_t) unsigned char buffer_[InlineBytes];
};

}  // namespace latsim::des
