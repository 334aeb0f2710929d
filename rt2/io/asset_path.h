// rt2/io/asset_path.h — where a file that an asset names lies (internal): a glTF's buffers
// and images, an OBJ's MTL libraries and an MTL's textures. Such a name is resolved against
// the asset's own folder and must stay inside it after `..` and symbolic links, unless the
// user allows otherwise (AssetPolicy::allow_outside_assets); a name with a URI scheme
// (http:, file:) is never read.
#pragma once

#include <string>

#include "rt2/base/asset_policy.h"

namespace rt2::io {

// Whether `path`, after `..` and symbolic links, lies in `folder` (resolved the same way),
// compared component by component (so /a/bc is not in /a/b).
bool lies_inside(const std::string& path, const std::string& folder);

// The path of the file `name` that the asset file `asset` refers to. Throws rt2::Error
// "`where`: '<name>' ..." when `name` has a URI scheme, or resolves outside the asset's
// folder and `policy` does not allow that. The file itself is not opened.
std::string asset_file(const std::string& asset, const std::string& name,
                       const AssetPolicy& policy, const std::string& where);

}  // namespace rt2::io
