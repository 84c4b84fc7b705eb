#include "scripting/stage_journal.h"

#include <cstdint>

namespace sdg::scripting {

namespace {
constexpr size_t kCreatedHere = SIZE_MAX;
}

StageJournal::PrimRecord* StageJournal::recordFor(const Prim& prim) {
  auto [it, inserted] = index_.try_emplace(&prim, records_.size());
  if (it->second == kCreatedHere) return nullptr;
  if (inserted) records_.push_back(PrimRecord{prim.path(), {}});
  return &records_[it->second];
}

bool StageJournal::has(const PrimRecord& record, Field field, const std::string& attribute) {
  for (const Saved& s : record.saved)
    if (s.field == field && (field != Field::Attribute || s.attribute == attribute)) return true;
  return false;
}

void StageJournal::beforeAttributeWrite(const Prim& prim, const std::string& name) {
  PrimRecord* record = recordFor(prim);
  if (!record || has(*record, Field::Attribute, name)) return;
  Saved s{Field::Attribute, name, std::nullopt, {}, {}, std::nullopt};
  if (const Attribute* a = prim.findAttribute(name)) s.value = *a;
  record->saved.push_back(std::move(s));
}

void StageJournal::beforeXformWrite(const Prim& prim) {
  PrimRecord* record = recordFor(prim);
  if (!record || has(*record, Field::XformOps)) return;
  record->saved.push_back(Saved{Field::XformOps, {}, std::nullopt, prim.xformOps(), {}, std::nullopt});
}

void StageJournal::beforeSemanticsWrite(const Prim& prim) {
  PrimRecord* record = recordFor(prim);
  if (!record || has(*record, Field::Semantics)) return;
  record->saved.push_back(Saved{Field::Semantics, {}, std::nullopt, {}, prim.semantics(), std::nullopt});
}

void StageJournal::beforeMaterialWrite(const Prim& prim) {
  PrimRecord* record = recordFor(prim);
  if (!record || has(*record, Field::Material)) return;
  record->saved.push_back(Saved{Field::Material, {}, std::nullopt, {}, {}, prim.material()});
}

void StageJournal::created(const Prim& prim) {
  index_[&prim] = kCreatedHere;
  createdPaths_.push_back(prim.path());
}

void StageJournal::forget(const Prim& prim) {
  auto it = index_.find(&prim);
  if (it != index_.end() && it->second == kCreatedHere) index_.erase(it);
}

bool StageJournal::createdHere(const Prim& prim) const {
  auto it = index_.find(&prim);
  return it != index_.end() && it->second == kCreatedHere;
}

void StageJournal::undo(Stage& stage) {
  for (auto record = records_.rbegin(); record != records_.rend(); ++record) {
    Prim* prim = stage.find(record->path);
    if (!prim) continue;
    for (auto s = record->saved.rbegin(); s != record->saved.rend(); ++s) {
      switch (s->field) {
        case Field::Attribute:
          if (!s->value) {
            prim->removeAttribute(s->attribute);
          } else {
            Attribute& a = prim->setAttribute(s->attribute, s->value->value, s->value->custom);
            a.doc = s->value->doc;
            a.loc = s->value->loc;
          }
          break;
        case Field::XformOps: prim->xformOps() = s->ops; break;
        case Field::Semantics: prim->semantics() = s->semantics; break;
        case Field::Material: prim->material() = s->material; break;
      }
    }
  }
  for (auto path = createdPaths_.rbegin(); path != createdPaths_.rend(); ++path) stage.removePrim(*path);
  index_.clear();
  records_.clear();
  createdPaths_.clear();
}

}  // namespace sdg::scripting
