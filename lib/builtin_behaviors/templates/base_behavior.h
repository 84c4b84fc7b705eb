#pragma once
// BaseBehavior — a template base class for a family of behaviors: it owns
// the `interval` variable and its counting, so a subclass only adds its own
// variables and writes apply(). Unlike the randomizers it does not apply on
// play (as Isaac Sim's BaseBehavior): the first apply comes with an update.
#include <string>
#include <vector>

#include "behavior/behavior.h"

namespace templates {

class BaseBehavior : public sdg::Behavior {
 public:
  void onPlay() override { interval_ = var<uint32_t>("interval"); }
  void onUpdate(double, double dt) override {
    if (dt <= 0) return;
    if (interval_ == 0 || ++counter_ >= interval_) {
      apply();
      counter_ = 0;
    }
  }
  void onStop() override { interval_ = counter_ = 0; }

  // The variables every subclass has; append yours after them.
  static std::vector<sdg::AttributeSpec> baseVariables() {
    sdg::AttributeSpec interval;
    interval.name = "interval";
    interval.type = sdg::ValueType::UInt;
    interval.defaultValue = sdg::Value::makeUInt(0);
    interval.doc = "Apply every N updates; 0 means every update.";
    return {interval};
  }

 protected:
  virtual void apply() = 0;

 private:
  uint32_t interval_ = 0;
  uint32_t counter_ = 0;
};

}  // namespace templates
