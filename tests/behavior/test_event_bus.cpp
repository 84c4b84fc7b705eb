#include <catch2/catch.hpp>

#include "behavior/event_bus.h"

using namespace sdg;

TEST_CASE("event bus: delivery once per dispatch, in publish order", "[behavior][events]") {
  EventBus bus;
  std::vector<std::string> seen;
  bus.subscribe("a", [&](const Payload& p) { seen.push_back("a:" + std::string(p.getString("k"))); });
  bus.subscribe("b", [&](const Payload& p) { seen.push_back("b:" + std::string(p.getString("k"))); });
  bus.publish("b", {{"k", std::string("1")}});
  bus.publish("a", {{"k", std::string("2")}});
  bus.publish("c", {});  // nobody listens
  CHECK(seen.empty());  // nothing is delivered before the update
  CHECK(bus.dispatch() == 3);
  CHECK(seen == std::vector<std::string>{"b:1", "a:2"});
  CHECK(bus.dispatch() == 0);
}

TEST_CASE("event bus: replies published while dispatching arrive next update", "[behavior][events]") {
  EventBus bus;
  int replies = 0;
  bus.subscribe("ping", [&](const Payload&) { bus.publish("pong", {}); });
  bus.subscribe("pong", [&](const Payload&) { ++replies; });
  bus.publish("ping", {});
  bus.dispatch();
  CHECK(replies == 0);
  bus.dispatch();
  CHECK(replies == 1);
}

TEST_CASE("event bus: unsubscribe and payload matching", "[behavior][events]") {
  EventBus bus;
  int calls = 0;
  auto id = bus.subscribe("x", [&](const Payload&) { ++calls; });
  bus.unsubscribe(id);
  bus.publish("x", {});
  bus.dispatch();
  CHECK(calls == 0);
  Payload reply{{"prim_path", std::string("/A")}, {"state_name", std::string("SETUP")}, {"state", 1.0}};
  CHECK(reply.contains({{"state_name", std::string("SETUP")}}));
  CHECK_FALSE(reply.contains({{"state_name", std::string("RESET")}}));
  CHECK_FALSE(reply.contains({{"state", std::string("1")}}));  // types must match too
}
