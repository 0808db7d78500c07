#pragma once
// The per-particle state a scheme declares once, by name: Particles keep each declared column as
// long as the particles (owned and ghost slots), and migration, removal, checkpoints and frames go
// over the declarations instead of being handed the scheme's arrays (docs/developer.md, "A scheme's
// fields").
#include <deque>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "src/core/types.hpp"
#include "src/particles/particle_field.hpp"

namespace sph {

// What a declared field is for (bit flags).
enum FieldUse : unsigned {
  // State carried from one step to the next: it moves with its particle when particles migrate or
  // leave the run, and checkpoints save it. One flag for both: a restart puts the particles in order
  // again, so a field that moved but was not saved would make restarts differ.
  kCarried = 1u,
  // Written to every frame, under its name (scalar fields).
  kWritten = 2u,
  // With kCarried: a field a checkpoint may lack (one written before the field existed), read back
  // as zeros; its owner tells from the checkpoint's header whether it was saved.
  kOptional = 4u,
};

// A declared field's handle; T is double or Vector<D>.
template <class T> struct FieldId {
  std::size_t index = static_cast<std::size_t>(-1);
  bool valid() const { return index != static_cast<std::size_t>(-1); }  // declared
};

template <int D> class FieldRegistry {
 public:
  // Declares a field with zero values on `rows` particles, or returns the one declared before under
  // this name (a scheme set up twice on the same particles); a name taken by another shape is refused.
  FieldId<double> declare_scalar(const std::string& name, unsigned uses, std::size_t rows) {
    return {declare(scalars_, name, uses, rows)};
  }
  FieldId<Vector<D>> declare_vector(const std::string& name, unsigned uses, std::size_t rows) {
    return {declare(vectors_, name, uses, rows)};
  }

  std::vector<double>& operator[](FieldId<double> f) { return scalars_.at(f.index).values; }
  const std::vector<double>& operator[](FieldId<double> f) const { return scalars_.at(f.index).values; }
  std::vector<Vector<D>>& operator[](FieldId<Vector<D>> f) { return vectors_.at(f.index).values; }
  const std::vector<Vector<D>>& operator[](FieldId<Vector<D>> f) const { return vectors_.at(f.index).values; }

  // Whether f is one of the registry's columns.
  bool holds(const std::vector<double>& f) const {
    for (const auto& c : scalars_)
      if (&c.values == &f) return true;
    return false;
  }
  bool holds(const std::vector<Vector<D>>& f) const {
    for (const auto& c : vectors_)
      if (&c.values == &f) return true;
    return false;
  }

  // f(column) for every column, scalar and vector.
  template <class Fn> void for_each_column(Fn&& f) {
    for (auto& c : scalars_) f(c.values);
    for (auto& c : vectors_) f(c.values);
  }

  // Every column to `rows` (new rows zero): Particles call it as particles come and go.
  void resize(std::size_t rows) {
    for (auto& c : scalars_) c.values.resize(rows, 0.0);
    for (auto& c : vectors_) c.values.resize(rows, Vector<D>::Zero());
  }
  void push_back() {
    for (auto& c : scalars_) c.values.push_back(0.0);
    for (auto& c : vectors_) c.values.push_back(Vector<D>::Zero());
  }
  // Row `from` into row `to` of every column (removal compacts the owned rows).
  void copy_row(std::size_t to, std::size_t from) {
    for (auto& c : scalars_) c.values[to] = c.values[from];
    for (auto& c : vectors_) c.values[to] = c.values[from];
  }

  // The fields with `use`, in declaration order, as views of their first `rows` rows (rows * components
  // doubles each). A scheme may keep a column shorter between steps only above `rows`.
  std::vector<ParticleField> with(FieldUse use, std::size_t rows) {
    std::vector<ParticleField> out;
    for (const Entry& e : order_) {
      if (e.vector && (vectors_[e.index].uses & use)) out.push_back(view(vectors_[e.index], rows));
      if (!e.vector && (scalars_[e.index].uses & use)) out.push_back(view(scalars_[e.index], rows));
    }
    return out;
  }
  // The scalar fields with `use`, in declaration order (every row: owned and ghost).
  std::vector<ScalarField> scalars_with(FieldUse use) const {
    std::vector<ScalarField> out;
    for (const Entry& e : order_)
      if (!e.vector && (scalars_[e.index].uses & use))
        out.push_back({scalars_[e.index].name, &scalars_[e.index].values});
    return out;
  }
  // The scalar field named `name` if one is declared with `use`, or null.
  const std::vector<double>* find_scalar(const std::string& name, FieldUse use) const {
    for (const auto& c : scalars_)
      if (c.name == name && (c.uses & use)) return &c.values;
    return nullptr;
  }

 private:
  template <class T> struct Column {
    std::string name;
    unsigned uses;
    std::vector<T> values;
  };
  struct Entry {
    bool vector;
    std::size_t index;
  };

  template <class T>
  std::size_t declare(std::deque<Column<T>>& columns, const std::string& name, unsigned uses, std::size_t rows) {
    for (std::size_t k = 0; k < columns.size(); ++k)
      if (columns[k].name == name) {
        columns[k].uses = uses;
        return k;
      }
    for (const Entry& e : order_)
      if ((e.vector ? vectors_[e.index].name : scalars_[e.index].name) == name)
        throw std::logic_error("particle field '" + name + "' declared twice with different components");
    if constexpr (std::is_same_v<T, double>) columns.push_back({name, uses, std::vector<T>(rows, 0.0)});
    else columns.push_back({name, uses, std::vector<T>(rows, T::Zero())});
    order_.push_back({std::is_same_v<T, Vector<D>>, columns.size() - 1});
    return columns.size() - 1;
  }
  // A view of the column's first `rows` rows.
  template <class T> static ParticleField view(Column<T>& c, std::size_t rows) {
    if (c.values.size() < rows)
      throw std::logic_error("particle field '" + c.name + "' has fewer rows than owned particles");
    if constexpr (std::is_same_v<T, double>) return {c.name, c.values.data(), 1};
    else return {c.name, c.values.empty() ? nullptr : c.values[0].data(), D};
  }

  std::deque<Column<double>> scalars_;  // a deque: references to a column survive later declarations
  std::deque<Column<Vector<D>>> vectors_;
  std::vector<Entry> order_;  // declaration order across both kinds: the checkpoint's field order
};

}  // namespace sph
