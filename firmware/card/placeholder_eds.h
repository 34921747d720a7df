// The file the card serves as its EDS until the EDS generator (issue 19, part A) provides the one built
// from the firmware's tables: a short text that says what it is, so a scanner's upload and the web
// page's download have real bytes to carry (docs/file-object.md "Which file").
#pragma once

#include "cip/file_object.h"

namespace firmware {

cip::ServedFile PlaceholderEds();

}  // namespace firmware
