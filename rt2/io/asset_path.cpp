// rt2/io/asset_path.cpp — names an asset gives, resolved and confined (rt2/io/asset_path.h).
#include "rt2/io/asset_path.h"

#include <algorithm>
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

// Whether `p` is `folder` or lies below it (both absolute and normal).
bool inside(const fs::path& folder, const fs::path& p) {
  auto f = folder.begin(), q = p.begin();
  for (; f != folder.end(); ++f, ++q) {
    if (f->empty()) continue;  // the trailing "" of "dir/"
    if (q == p.end() || *f != *q) return false;
  }
  return true;
}

}  // namespace

std::string asset_file(const std::string& asset, const std::string& name,
                       const AssetPolicy& policy, const std::string& where) {
  if (const std::string s = scheme(name); !s.empty())
    throw Error(one_line(where + ": '" + name + "' is a URI with scheme '" + s +
                         "'; rt2 reads files beside the asset and data: URIs only"));
  const fs::path folder = fs::path(asset).parent_path();
  const fs::path p = fs::path(name).is_absolute() ? fs::path(name) : folder / name;
  if (policy.allow_outside_assets) return p.string();
  std::error_code ec;
  const fs::path real_folder = fs::weakly_canonical(folder.empty() ? fs::path(".") : folder, ec);
  const fs::path real = ec ? fs::path() : fs::weakly_canonical(p, ec);
  if (ec || !inside(real_folder, real))
    throw Error(one_line(where + ": '" + name + "' lies outside the folder of " +
                         fs::path(asset).filename().string() +
                         " (rt2cpr --allow-outside-assets reads it)"));
  return real.string();
}

}  // namespace rt2::io
