// The card's EDS (Electronic Data Sheet, CIP Vol. 1 ch. 7; docs/eds.md), written from the tables the
// firmware serves: the Identity values (identity_object.h), the drive assemblies and connection points
// (cip/drive/assembly_codec.h), the RPI limits of the Connection Manager (ConnectionManagerOptions),
// and the parameter table (drive_link/parameter_table.h) as the Parameter object 0x0F shows it.
//
// Streaming and deterministic: the text goes to an EdsSink piece by piece, never whole in memory, and
// the same model always gives the same bytes, so a reader of any window can run the writer again and
// keep only its window (EdsFile). Device-path code: no heap, no exceptions, no iostream.
#pragma once

#include <string_view>

#include "cip/providers.h"

namespace cip::eds {

class EdsSink {
 public:
  // Takes the next piece of the text. False: the sink wants no more (the writer stops early).
  virtual bool Append(std::string_view text) = 0;

 protected:
  ~EdsSink() = default;
};

// Writes the EDS of the card on `model` (its product code and name, its parameter limits).
void WriteEds(DriveModel model, EdsSink& sink);

// The file name an EDS of `model` is published under (IPE002Z_VF-MB1.eds).
std::string_view EdsFileName(DriveModel model);

}  // namespace cip::eds
