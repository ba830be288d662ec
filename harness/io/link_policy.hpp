// Whether a path's last component may be a symbolic link that is followed. A path the user names
// on the command line is theirs to point anywhere (Links::follow); an entry of a folder that
// dropcheck reads or fills (a baseline folder) is data from whoever made the folder, and a link
// there could lead a read or a write out of it (Links::refuse).
#pragma once

namespace dropcheck {

enum class Links { follow, refuse };

}  // namespace dropcheck
