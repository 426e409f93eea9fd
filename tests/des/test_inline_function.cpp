// The small-buffer callable that holds event callbacks.
#include <catch2/catch.hpp>

#include <array>
#include <memory>

#include "latsim/des/inline_function.hpp"

using Fn = latsim::des::InlineFunction<int(int), 32>;

TEST_CASE("inline function stores small callables inline and large ones on the heap", "[inline_function]") {
  struct Small {
    void* a;
    void* b;
    int c;
    int operator()(int x) const { return x + c; }
  };
  struct Large {
    std::array<int, 40> data{};
    int operator()(int x) const { return x + data[39]; }
  };
  STATIC_REQUIRE(Fn::stores_inline<Small>);
  STATIC_REQUIRE_FALSE(Fn::stores_inline<Large>);

  Fn small = Small{nullptr, nullptr, 5};
  CHECK(small(1) == 6);
  Large big;
  big.data[39] = 7;
  Fn large = big;
  CHECK(large(1) == 8);
  Fn moved = std::move(large);
  CHECK_FALSE(large);  // NOLINT(bugprone-use-after-move): moved-from is empty by contract
  CHECK(moved(2) == 9);
}

TEST_CASE("inline function destroys captures exactly once", "[inline_function]") {
  auto token = std::make_shared<int>(3);
  {
    Fn f = [token](int x) { return x * *token; };
    CHECK(token.use_count() == 2);
    Fn g = std::move(f);
    CHECK(token.use_count() == 2);
    CHECK(g(2) == 6);
    g.reset();
    CHECK(token.use_count() == 1);
    g.assign([token](int x) { return x - *token; });
    CHECK(g(10) == 7);
    CHECK(token.use_count() == 2);
  }
  CHECK(token.use_count() == 1);

  std::array<std::shared_ptr<int>, 4> many{token, token, token, token};  // 64 bytes: heap
  {
    Fn h = [many](int x) { return x + static_cast<int>(many.size()); };
    CHECK(token.use_count() == 9);
    Fn h2 = std::move(h);
    CHECK(h2(1) == 5);
    CHECK(token.use_count() == 9);
  }
  CHECK(token.use_count() == 5);
}
