#pragma once
// The link table: the correspondence `bodygen build` uses, for people to
// review (`bodygen check --links`, `bodyview --contours`). The same stages as
// the pipeline up to its bands: excluded contours dropped, validation and
// repair, grouping into structures, nesting, correspondence per structure and
// slice pair (material regions: solids with solids, holes with holes), the stack's cuts and
// joins. Contours are named by their file reference (ContourRef).
//
// Which construction the pipeline then picks for a branch, or whether it
// detaches a branch it cannot build, is not part of the table.
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "builder/contours/validate.h"
#include "builder/correspondence/correspondence.h"
#include "shared/error.h"

namespace body {

enum class LinkOrigin : uint8_t {
    Computed,  // the correspondence links them and the build does
    Joined,    // a "join" override links them
    Cut,       // a "cut" override names them: no link is built (listed whether or not the
               // correspondence links them, e.g. once the cut split their unlabelled structure)
};
enum class LinkKind : uint8_t { Band, Branch };  // 1:1, or part of a 1:N / N:1 / N:M group

struct TableLink {
    std::string structure;  // structure id ("auto_N" for unlabelled groups)
    size_t slice = 0;       // the lower slice's index in the sorted, merged stack
    ContourRef lower, upper;
    bool hole = false;
    LinkKind kind = LinkKind::Band;  // of the built links' group (Cut links: Band)
    LinkOrigin origin = LinkOrigin::Computed;
};

// A contour where its structure ends: nothing linked above (`up`) or below;
// a contour linked to nothing has both.
struct TableEnd {
    std::string structure;
    size_t slice = 0;
    ContourRef contour;
    bool up = false;
};

struct LinkTable {
    std::vector<TableLink> links;  // by structure, then slice, solids before holes
    std::vector<TableEnd> ends;
    std::vector<ContourRef> excluded;  // as the links section lists them
};

// Errors are validation's (one line, exit code 2).
Result<LinkTable> compute_link_table(const ContourStack& stack, CorrespondenceMethod method,
                                     const RepairOptions& repair, const std::string& path);

const char* link_origin_name(LinkOrigin origin);  // "computed", "joined", "cut"
const char* link_kind_name(LinkKind kind);        // "band", "branch"

}  // namespace body
