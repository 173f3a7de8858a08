// In-memory named-field store: see state_store.hpp.
#include "common/state_store.hpp"

#include <cstring>

#include "common/errors.hpp"

namespace common {

namespace {
template <class T>
void put(std::map<std::string, StateStore::Field, std::less<>>& fields, std::string_view name,
         std::span<const T> data) {
  auto [it, inserted] = fields.emplace(std::string(name), std::vector<T>(data.begin(), data.end()));
  if (!inserted) throw InternalError("state field '" + std::string(name) + "' written twice");
}

template <class T>
std::vector<T> get(const std::map<std::string, StateStore::Field, std::less<>>& fields,
                   std::string_view name) {
  auto it = fields.find(name);
  if (it == fields.end()) throw InputError("state field '" + std::string(name) + "' is missing");
  const auto* v = std::get_if<std::vector<T>>(&it->second);
  if (v == nullptr) throw InputError("state field '" + std::string(name) + "' has the wrong type");
  return *v;
}

template <class T>
void append_pod(std::vector<char>& out, const T& value) {
  const auto* p = reinterpret_cast<const char*>(&value);
  out.insert(out.end(), p, p + sizeof(T));
}

template <class T>
T take_pod(std::span<const char> bytes, std::size_t& pos) {
  if (pos + sizeof(T) > bytes.size()) throw InputError("state buffer is truncated");
  T value;
  std::memcpy(&value, bytes.data() + pos, sizeof(T));
  pos += sizeof(T);
  return value;
}
}  // namespace

void StateStore::write(std::string_view name, std::span<const double> data) {
  put(fields_, name, data);
}
void StateStore::write(std::string_view name, std::span<const std::int64_t> data) {
  put(fields_, name, data);
}
std::vector<double> StateStore::read_f64(std::string_view name) const {
  return get<double>(fields_, name);
}
std::vector<std::int64_t> StateStore::read_i64(std::string_view name) const {
  return get<std::int64_t>(fields_, name);
}
bool StateStore::has(std::string_view name) const { return fields_.find(name) != fields_.end(); }

std::vector<char> StateStore::serialize() const {
  // The exact size first: one allocation, written once (a growing buffer of a 1 MB RVE state
  // reallocates a dozen times, each into fresh pages).
  std::size_t size = sizeof(std::uint64_t);
  for (const auto& [name, field] : fields_) {
    size += 2 * sizeof(std::uint64_t) + name.size() + sizeof(std::uint8_t);
    size += std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, field);
  }
  std::vector<char> out;
  out.reserve(size);
  append_pod(out, static_cast<std::uint64_t>(fields_.size()));
  for (const auto& [name, field] : fields_) {
    append_pod(out, static_cast<std::uint64_t>(name.size()));
    out.insert(out.end(), name.begin(), name.end());
    const auto kind = static_cast<std::uint8_t>(field.index());
    append_pod(out, kind);
    std::visit(
        [&out](const auto& v) {
          append_pod(out, static_cast<std::uint64_t>(v.size()));
          if (v.empty()) return;
          const auto* p = reinterpret_cast<const char*>(v.data());
          out.insert(out.end(), p, p + v.size() * sizeof(v[0]));
        },
        field);
  }
  return out;
}

StateStore StateStore::deserialize(std::span<const char> bytes) {
  StateStore store;
  std::size_t pos = 0;
  const auto count = take_pod<std::uint64_t>(bytes, pos);
  for (std::uint64_t i = 0; i < count; ++i) {
    const auto len = take_pod<std::uint64_t>(bytes, pos);
    if (pos + len > bytes.size()) throw InputError("state buffer is truncated");
    std::string name(bytes.data() + pos, len);
    pos += len;
    const auto kind = take_pod<std::uint8_t>(bytes, pos);
    const auto n = take_pod<std::uint64_t>(bytes, pos);
    auto read_vec = [&](auto tag) {
      using T = decltype(tag);
      if (pos + n * sizeof(T) > bytes.size()) throw InputError("state buffer is truncated");
      std::vector<T> v(n);
      if (n > 0) std::memcpy(v.data(), bytes.data() + pos, n * sizeof(T));
      pos += n * sizeof(T);
      // Moved in, not copied again (write() copies its span).
      if (!store.fields_.try_emplace(name, std::move(v)).second)
        throw InputError("state buffer holds field '" + name + "' twice");
    };
    if (kind == 0) {
      read_vec(double{});
    } else if (kind == 1) {
      read_vec(std::int64_t{});
    } else {
      throw InputError("state buffer has an unknown field kind");
    }
  }
  return store;
}

}  // namespace common
