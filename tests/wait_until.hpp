#pragma once
// Polls a condition until it holds or a timeout passes: for tests that watch another thread (a driver's reader,
// a pty peer) reach a state, without fixed sleeps.
#include <chrono>
#include <thread>

namespace fsd::test {

template <class Pred>
bool wait_until(Pred pred, double timeout_s = 5.0) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!pred()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

}  // namespace fsd::test
