// Tests harness/run/forked_text.cpp: the text a child computes comes back whole, an exception in
// the child comes back as its message, a child that dies is an error and never the caller's death,
// and the parent works while the child does.
#include "harness/run/forked_text.hpp"

#include <signal.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

using dropcheck::ForkedText;

TEST_CASE("a forked child's text comes back whole, as often as it is asked for", "[forked]") {
  const std::string big(300000, 'x');  // more than a pipe holds: the parent must drain it
  ForkedText child([&] { return "pid " + std::to_string(::getpid()) + " " + big; });
  const std::string text = child.get();
  CHECK(text.rfind("pid ", 0) == 0);
  CHECK(text.find("pid " + std::to_string(::getpid()) + " ") != 0);  // computed elsewhere
  CHECK(text.size() > big.size());
  CHECK(child.get() == text);
}

TEST_CASE("an exception in the child comes back as its message", "[forked]") {
  ForkedText child([]() -> std::string { throw std::invalid_argument("scene x.toml: bad key"); });
  CHECK_THROWS_WITH(child.get(), "scene x.toml: bad key");
}

TEST_CASE("a child that dies is an error, not the caller's end", "[forked]") {
  ForkedText child([]() -> std::string {
    ::raise(SIGKILL);
    return "never";
  });
  CHECK_THROWS_WITH(child.get(), Catch::Contains("signal 9"));
}

TEST_CASE("the parent goes on while the child works, and an uncollected child is reaped",
          "[forked]") {
  const auto start = std::chrono::steady_clock::now();
  {
    ForkedText slow([] {
      std::this_thread::sleep_for(std::chrono::seconds(30));
      return std::string("late");
    });
    // Here the parent is free; leaving the scope kills the child instead of waiting 30 s.
  }
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
}
