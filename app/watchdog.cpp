#include "app/watchdog.h"

#include <chrono>
#include <cstdlib>
#include <iostream>

namespace sizemesh {

Watchdog::Watchdog(double seconds, std::string message) {
  if (!(seconds > 0)) return;
  thread_ = std::thread([this, seconds, message = std::move(message)] {
    std::unique_lock<std::mutex> lock(mutex_);
    if (done_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return disarmed_; })) return;
    std::cerr << "sizemesh: error: " << message << std::endl;
    std::_Exit(1);
  });
}

Watchdog::~Watchdog() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    disarmed_ = true;
  }
  done_.notify_one();
  thread_.join();
}

}  // namespace sizemesh
