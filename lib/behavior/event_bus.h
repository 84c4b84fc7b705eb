#pragma once
// Named events with a small payload. publish() queues; dispatch() (once per
// update) delivers what was queued before it started, in publish order, to
// the subscribers of each name in subscription order. Events published while
// dispatching wait for the next update, so a reply is seen one update later.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/payload.h"

namespace sdg {

class EventBus {
 public:
  using Handler = std::function<void(const Payload&)>;
  using Subscription = uint64_t;

  Subscription subscribe(std::string name, Handler handler);
  void unsubscribe(Subscription id);
  void publish(std::string name, Payload payload);
  // Delivers the queued events; returns how many were delivered.
  size_t dispatch();
  size_t pending() const { return queue_.size(); }

 private:
  struct Subscriber {
    Subscription id;
    std::string name;
    Handler handler;
  };
  std::vector<Subscriber> subscribers_;
  std::vector<std::pair<std::string, Payload>> queue_;
  Subscription nextId_ = 1;
};

}  // namespace sdg
