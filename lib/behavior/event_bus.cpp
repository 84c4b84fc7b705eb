#include "behavior/event_bus.h"

#include <algorithm>

namespace sdg {

EventBus::Subscription EventBus::subscribe(std::string name, Handler handler) {
  subscribers_.push_back({nextId_, std::move(name), std::move(handler)});
  return nextId_++;
}

void EventBus::unsubscribe(Subscription id) {
  std::erase_if(subscribers_, [id](const Subscriber& s) { return s.id == id; });
}

void EventBus::publish(std::string name, Payload payload) { queue_.emplace_back(std::move(name), std::move(payload)); }

size_t EventBus::dispatch() {
  std::vector<std::pair<std::string, Payload>> batch;
  batch.swap(queue_);
  for (const auto& [name, payload] : batch) {
    // Copy the ids first: a handler may subscribe or unsubscribe.
    std::vector<Subscription> ids;
    for (const Subscriber& s : subscribers_)
      if (s.name == name) ids.push_back(s.id);
    for (Subscription id : ids) {
      auto it = std::find_if(subscribers_.begin(), subscribers_.end(), [id](const Subscriber& s) { return s.id == id; });
      if (it == subscribers_.end()) continue;
      Handler handler = it->handler;  // the vector may grow during the call
      handler(payload);
    }
  }
  return batch.size();
}

}  // namespace sdg
