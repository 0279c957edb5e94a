// web_files.hpp — where the page's files and three.js are, found from the executable's folder
// (never the working folder): installed, <prefix>/share/knit/serve (three.js in its three/);
// in the build tree, the source's apps/serve/web and the build's node/node_modules/three.
#pragma once
#include <string>

namespace knit::serve {

struct WebFiles {
    std::string page;   // index.html, app.js, ...
    std::string three;  // the npm package three (build/, examples/jsm/)
};

// Throws knit::Error listing the folders it looked in when either is missing.
WebFiles findWebFiles(const std::string& executable);

// The running executable (/proc/self/exe).
std::string executablePath();

}  // namespace knit::serve
