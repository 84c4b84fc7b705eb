#include "stage/stage.h"

#include <algorithm>
#include <stdexcept>

#include "stage/path.h"

namespace sdg {

Stage::Stage() : root_(std::make_unique<Prim>("/", PrimType::Scope, nullptr)) {
  byPath_.emplace(root_->path(), root_.get());
}

Stage::Stage(const Stage& other) : Stage() { *this = other; }

Stage& Stage::operator=(const Stage& other) {
  if (this == &other) return *this;
  Stage fresh;
  fresh.metadata_ = other.metadata_;
  fresh.animation_ = other.animation_;
  other.traverse([&](const Prim& p) {
    Prim& copy = fresh.definePrim(p.path(), p.type());
    copy.attributes_ = p.attributes_;
    copy.xformOps_ = p.xformOps_;
    copy.semantics_ = p.semantics_;
    copy.material_ = p.material_;
    copy.behaviors_ = p.behaviors_;
    copy.metadata_ = p.metadata_;
    copy.loc_ = p.loc_;
  });
  *this = std::move(fresh);
  return *this;
}

Prim& Stage::definePrim(const std::string& primPath, PrimType type) {
  if (std::string why = path::whyInvalid(primPath); !why.empty())
    throw std::logic_error("definePrim(" + primPath + "): " + why);
  if (byPath_.count(primPath)) throw std::logic_error("definePrim(" + primPath + "): already defined");
  Prim* parent = find(path::parent(primPath));
  if (!parent) throw std::logic_error("definePrim(" + primPath + "): parent is not defined");
  auto prim = std::make_unique<Prim>(primPath, type, parent);
  Prim* raw = prim.get();
  parent->children_.push_back(raw);
  byPath_.emplace(raw->path(), raw);
  owned_.emplace(primPath, std::move(prim));
  return *raw;
}

bool Stage::removePrim(std::string_view primPath) {
  Prim* prim = find(primPath);
  if (!prim || prim->isPseudoRoot()) return false;
  std::vector<Prim*> doomed = subtree(*prim);
  auto& siblings = prim->parent_->children_;
  siblings.erase(std::find(siblings.begin(), siblings.end(), prim));
  // Erase the index entries first: their keys view strings the prims own.
  for (Prim* p : doomed) byPath_.erase(p->path());
  for (Prim* p : doomed) {
    std::string key = p->path();
    owned_.erase(key);
  }
  return true;
}

Prim* Stage::find(std::string_view primPath) {
  auto it = byPath_.find(primPath);
  return it == byPath_.end() ? nullptr : it->second;
}

const Prim* Stage::find(std::string_view primPath) const {
  auto it = byPath_.find(primPath);
  return it == byPath_.end() ? nullptr : it->second;
}

namespace {
template <typename PrimT, typename Visit>
void visitBelow(PrimT& prim, const Visit& visit) {
  // Explicit stack: hostile scenes may nest deeply.
  std::vector<PrimT*> stack(prim.children().rbegin(), prim.children().rend());
  while (!stack.empty()) {
    PrimT* p = stack.back();
    stack.pop_back();
    visit(*p);
    stack.insert(stack.end(), p->children().rbegin(), p->children().rend());
  }
}
}  // namespace

void Stage::traverse(const std::function<void(const Prim&)>& visit) const {
  visitBelow<const Prim>(*root_, visit);
}

void Stage::traverse(const std::function<void(Prim&)>& visit) { visitBelow<Prim>(*root_, visit); }

std::vector<Prim*> Stage::subtree(Prim& start) {
  std::vector<Prim*> out{&start};
  visitBelow<Prim>(start, [&](Prim& p) { out.push_back(&p); });
  return out;
}

Matrix4d Stage::worldMatrix(const Prim& prim) const {
  Matrix4d m = Matrix4d::Identity();
  for (const Prim* p = &prim; p && !p->isPseudoRoot(); p = p->parent()) m = p->localMatrix() * m;
  return m;
}

bool Stage::operator==(const Stage& other) const {
  if (metadata_ != other.metadata_ || primCount() != other.primCount()) return false;
  std::vector<const Prim*> mine, theirs;
  traverse([&](const Prim& p) { mine.push_back(&p); });
  other.traverse([&](const Prim& p) { theirs.push_back(&p); });
  for (size_t i = 0; i < mine.size(); ++i)
    if (!mine[i]->sameContent(*theirs[i])) return false;
  return true;
}

}  // namespace sdg
