// Tests of the job schema itself: consistent paths, documented keys, no defaults on physics.
#include "app/schema.hpp"

#include <gtest/gtest.h>

TEST(Schema, EveryKeyHasADocumentedParentSection) {
  const auto& s = app::job_schema();
  for (const auto& k : s.keys) {
    EXPECT_FALSE(k.doc.empty()) << k.path;
    const std::string parent = app::parent_path(k.path);
    if (parent.empty()) continue;
    const app::Key* p = s.find(parent);
    ASSERT_NE(p, nullptr) << k.path << " has no parent section " << parent;
    EXPECT_TRUE(p->type == app::Type::Table || p->type == app::Type::TableList) << parent;
  }
}

TEST(Schema, KeysAreUniqueAndDefaultsHaveTheirKeysType) {
  const auto& s = app::job_schema();
  for (std::size_t i = 0; i < s.keys.size(); ++i) {
    for (std::size_t j = i + 1; j < s.keys.size(); ++j) EXPECT_NE(s.keys[i].path, s.keys[j].path);
    const auto& k = s.keys[i];
    EXPECT_FALSE(k.required && k.fallback) << k.path << " is required and has a default";
    if (!k.fallback) continue;
    switch (k.type) {
      case app::Type::Float:
        EXPECT_TRUE(std::holds_alternative<double>(*k.fallback)) << k.path;
        break;
      case app::Type::Int:
        EXPECT_TRUE(std::holds_alternative<std::int64_t>(*k.fallback)) << k.path;
        break;
      case app::Type::String:
        EXPECT_TRUE(std::holds_alternative<std::string>(*k.fallback)) << k.path;
        break;
      default:
        break;
    }
  }
}

TEST(Schema, PhysicalParametersHaveNoDefaults) {
  for (const auto& k : app::job_schema().keys) {
    if (k.path.starts_with("dem.material.") || k.path.starts_with("mpm.elastic.") ||
        k.path.ends_with(".density") || k.path.ends_with(".pressure")) {
      EXPECT_FALSE(k.fallback.has_value()) << k.path << " is physical and must not have a default";
    }
  }
}
