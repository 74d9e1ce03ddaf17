// Where the toolkit's data files live (the nominal robot, the scenario
// library): the folders of the source tree the binary was built from, or the
// folder named by the environment variable GPM_DATA_DIR (holding models/ and
// scenarios/).
#pragma once

#include <string>

namespace gpm {

// Folder holding gpm2002.yaml and gpm2002.xml.
std::string models_dir();

// Folder holding the scenario library (*.yaml).
std::string scenarios_dir();

}  // namespace gpm
