// rt2/io/asset_path.cpp — names an asset gives, resolved and confined (rt2/io/asset_path.h).
#include "rt2/io/asset_path.h"

#include <cctype>
#include <filesystem>
#include <system_error>

#include "rt2/base/error.h"
#include "rt2/io/text.h"

namespace rt2::io {

namespace fs = std::filesystem;

namespace {

// The scheme of a URI ("http" of "http://x"), or "" for a path. One letter before the
// colon is a Windows drive, which this folder-relative reading treats as a file name.
std::string scheme(const std::string& name) {
  const std::size_t colon = name.find(':');
  if (colon == std::string::npos || colon < 2 || !std::isalpha(static_cast<unsigned char>(name[0])))
    return {};
  for (std::size_t i = 1; i < colon; ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') return {};
  }
  return name.substr(0, colon);
}

// `p` after `..` and symbolic links, absolute (lexically, where it cannot be resolved).
fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(p.empty() ? fs::path(".") : p, ec);
  if (ec) r = fs::absolute(p, ec).lexically_normal();
  if (r.has_relative_path() && r.filename().empty()) r = r.parent_path();  // "a/b/": "a/b"
  return r;
}

}  // namespace

bool lies_inside(const std::string& path, const std::string& folder) {
  const fs::path p = resolved(path), f = resolved(folder);
  auto q = p.begin();
  for (auto it = f.begin(); it != f.end(); ++it, ++q)
    if (q == p.end() || *q != *it) return false;
  return true;
}

std::string asset_file(const std::string& asset, const std::string& name, const AssetPolicy& policy,
                       const std::string& where) {
  if (const std::string s = scheme(name); !s.empty())
    throw Error(one_line(where + ": '" + name + "' is a URI with scheme '" + s +
                         "'; rt2 reads files beside the asset and data: URIs only"));
  const fs::path folder = fs::path(asset).parent_path();
  const fs::path p = fs::path(name).is_absolute() ? fs::path(name) : folder / name;
  if (policy.allow_outside_assets) return p.string();
  if (!lies_inside(p.string(), folder.string()))
    throw Error(one_line(where + ": '" + name + "' lies outside the folder of " +
                         fs::path(asset).filename().string() +
                         " (--allow-outside-assets reads it)"));
  return resolved(p).string();
}

}  // namespace rt2::io
