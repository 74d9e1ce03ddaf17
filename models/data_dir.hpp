// Where the toolkit's data files live (the nominal robot, the scenario
// library). The data root holds models/ and scenarios/; the first that exists:
//   1. the folder named by the environment variable GPM_DATA_DIR;
//   2. an installed data folder next to the binary holding this code:
//      PREFIX/share/gpm for an executable in PREFIX/bin, a library in
//      PREFIX/lib or a Python module in PREFIX/lib/python3/dist-packages
//      (`cmake --install build --prefix PREFIX` puts the data there; the
//      install can be moved as a whole);
//   3. the source tree the binary was built from (the build tree's case).
// Consumers that link the static libraries into a program outside PREFIX get
// PREFIX/share/gpm from the CMake package (gpm_DATA_DIR) and set GPM_DATA_DIR.
#pragma once

#include <string>

namespace gpm {

// Folder holding models/ and scenarios/ (the rules above).
std::string data_root();

// Folder holding gpm2002.yaml and gpm2002.xml.
std::string models_dir();

// Folder holding the scenario library (*.yaml).
std::string scenarios_dir();

}  // namespace gpm
