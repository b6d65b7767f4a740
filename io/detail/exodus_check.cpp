// Exodus II contents checked through netCDF before VTK's reader sees them: VTK indexes its
// point arrays with the connectivity it reads and trusts every count, so an element id past
// the node count crashes it (or, one past the end, reads garbage). Every variable VTK reads by
// index is checked here: block connectivity (n-sided counts; polyhedra: their face lists and
// the face blocks' nodes), side sets, node sets, and the shapes of coordinates, maps and result
// variables.

#include <io/detail/common.h>
#include <io/detail/netcdf_file.h>
#include <io/detail/readers.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <netcdf.h>
#include <optional>
#include <vector>

namespace tr::io_detail {

namespace {

// A variable's dimensions must be exactly `expected` (names); `what` names it in the message.
void expect_shape(const NetcdfFile& file, int var_id, const std::string& what,
                  const std::vector<std::string>& expected) {
    const std::vector<int> dims = file.var_dims(var_id);
    bool ok = dims.size() == expected.size();
    for (std::size_t k = 0; ok && k < dims.size(); ++k) {
        const std::optional<int> want = file.dim(expected[k]);
        ok = want.has_value() && dims[k] == *want;
    }
    if (!ok) {
        std::string shape;
        for (const std::string& e : expected) shape += (shape.empty() ? "" : ", ") + e;
        fail(ErrorCode::kParse, "'" + what + "' must have the dimensions (" + shape + ")",
             file.where());
    }
}

// Every value of `var_name` (when present) must lie in [1, limit].
void expect_ids_in_range(const NetcdfFile& file, const std::string& var_name,
                         const std::string& what, std::size_t limit,
                         const std::string& limit_what) {
    const std::optional<int> var = file.var(var_name);
    if (!var) return;
    file.for_each_value(*var, var_name, [&](std::size_t i, long long v) {
        if (v < 1 || static_cast<unsigned long long>(v) > limit) {
            fail(ErrorCode::kParse,
                 "Exodus II " + what + " (" + var_name + "): entry " + std::to_string(i) + " is " +
                     std::to_string(v) + ", outside 1.." + std::to_string(limit) + " (" +
                     limit_what + ")",
                 file.where());
        }
    });
}

// `counts_name` holds one count per entity (each in [min_count, what is left]) of the list
// `list_name`, whose length (the dimension `list_dim`) they must sum to exactly: VTK walks the
// list by these counts without checking either. `owner` ("element block 1") and `entity`
// ("element", "face") and `items` ("nodes", "faces") name them in the message.
void expect_counts_cover_list(const NetcdfFile& file, const std::string& owner,
                              const std::string& counts_name, const std::string& count_dim,
                              const std::string& list_name, const std::string& list_dim,
                              const std::string& entity, const std::string& items,
                              long long min_count) {
    const std::optional<int> counts = file.var(counts_name);
    const std::optional<int> list = file.var(list_name);
    if (!counts || !list) {
        fail(ErrorCode::kParse,
             "Exodus II " + owner + " needs both '" + list_name + "' and '" + counts_name + "'",
             file.where());
    }
    expect_shape(file, *counts, counts_name, {count_dim});
    expect_shape(file, *list, list_name, {list_dim});
    const std::size_t length = file.length(list_dim);
    std::size_t sum = 0;
    file.for_each_value(*counts, counts_name, [&](std::size_t i, long long v) {
        if (v < min_count || static_cast<unsigned long long>(v) > length - sum) {
            fail(ErrorCode::kParse,
                 "Exodus II " + owner + " (" + counts_name + "): " + entity + " " +
                     std::to_string(i + 1) + " has " + std::to_string(v) + " " + items +
                     (v < min_count ? " (at least " + std::to_string(min_count) + " needed)"
                                    : ", but its list (" + list_name + ") has " +
                                          std::to_string(length - sum) + " entries left"),
                 file.where());
        }
        sum += static_cast<std::size_t>(v);
    });
    if (sum != length) {
        fail(ErrorCode::kParse,
             "Exodus II " + owner + " (" + counts_name + "): " + entity + " " + items +
                 " counts sum to " + std::to_string(sum) + ", its list (" + list_name + ") has " +
                 std::to_string(length) + " entries",
             file.where());
    }
}

// Every value of the list `list_name` refers to an item (node, face) in 1..limit; `owner`
// names the block, `limit_what` the limit in the message.
void expect_refs_in_range(const NetcdfFile& file, const std::string& owner,
                          const std::string& list_name, const std::string& item, std::size_t limit,
                          const std::string& limit_what) {
    const std::optional<int> list = file.var(list_name);
    if (!list) return;
    file.for_each_value(*list, list_name, [&](std::size_t i, long long v) {
        if (v < 1 || static_cast<unsigned long long>(v) > limit) {
            fail(ErrorCode::kParse,
                 "Exodus II " + owner + " (" + list_name + "): entry " + std::to_string(i + 1) +
                     " refers to " + item + " " + std::to_string(v) + ", outside 1.." +
                     std::to_string(limit) + " (" + limit_what + ")",
                 file.where());
        }
    });
}

// A block's element type (its connectivity's attribute elem_type), upper-cased and cut at its
// first NUL (padding).
std::string element_type(const NetcdfFile& file, int conn) {
    std::string type = file.upper_text_attribute(conn, "elem_type");
    type.resize(std::min(type.size(), type.find('\0')));
    return type;
}

// A block's connectivity names its element type (attribute elem_type): without it the Exodus
// library cannot describe the block, and VTK's reader skips it but still counts it, then
// dereferences a null naming the blocks (GetSortedObjectInfo; fuzz_exodus, third run).
void expect_element_type(const NetcdfFile& file, int conn, const std::string& owner,
                         const std::string& conn_name) {
    if (file.upper_text_attribute(conn, "elem_type").find_first_not_of(" ") == std::string::npos) {
        fail(ErrorCode::kParse,
             "Exodus II " + owner + " (" + conn_name +
                 ") has no element type (its text attribute 'elem_type')",
             file.where());
    }
}

// VTK's reader takes a cell's node count from the first three letters of the element type
// (TET 4, HEX 8, ...; more nodes pick a quadratic cell or are read as the first ones) and reads
// that many from each element's row of num_nod_per_el: a shorter row reads past the block's list
// (heap garbage as node ids: a SEGV in AssembleOutputPoints, fuzz_exodus, eleventh run, for a
// TETRA4 block of 3 nodes an element).
void expect_nodes_for_type(const NetcdfFile& file, int conn, const std::string& owner,
                           const std::string& conn_name, std::size_t per_element,
                           const std::string& per_element_name) {
    struct Minimum {
        const char* prefix;
        std::size_t nodes;
    };
    static constexpr Minimum kMinimum[] = {
        {"CIR", 1}, {"SPH", 1}, {"BAR", 2}, {"TRU", 2}, {"BEA", 2}, {"EDG", 2}, {"STR", 2},
        {"TRI", 3}, {"SHE", 3}, {"QUA", 4}, {"TET", 4}, {"PYR", 5}, {"WED", 6}, {"HEX", 8}};
    const std::string type = element_type(file, conn);
    for (const Minimum& m : kMinimum) {
        if (type.rfind(m.prefix, 0) == 0 && per_element < m.nodes) {
            fail(ErrorCode::kParse,
                 "Exodus II " + owner + " (" + conn_name + "): element type " + type +
                     " needs at least " + std::to_string(m.nodes) + " nodes an element, not " +
                     std::to_string(per_element) + " ('" + per_element_name + "')",
                 file.where());
        }
    }
}

// The sides a side set may name on an element of `type` (0: none), by the first three letters
// as VTK's reader types cells: a circle or sphere is a vertex, whose side VTK's InsertSetSides
// looks up in no table (SEGV; fuzz_exodus, thirteenth run). Types not listed: 6, the bound
// for any element.
int sides_of_type(const std::string& type) {
    struct Sides {
        const char* prefix;
        int sides;
    };
    static constexpr Sides kSides[] = {{"CIR", 0}, {"SPH", 0}, {"SUP", 0}, {"TET", 4},
                                       {"WED", 5}, {"PYR", 5}, {"HEX", 6}};
    for (const Sides& s : kSides) {
        if (type.rfind(s.prefix, 0) == 0) return s.sides;
    }
    return 6;
}

// Face blocks (`fbconn<k>`): the faces polyhedral elements are made of. An NSIDED block lists
// each face's node count in `fbepecnt<k>`; any other has `num_nod_per_fa<k>` nodes a face. Every
// node id within the file's node count. Returns the number of faces of each block.
std::vector<std::size_t> check_face_blocks(const NetcdfFile& file, std::size_t num_nodes) {
    std::vector<std::size_t> faces;
    const std::size_t num_face_blocks = file.length("num_fa_blk");
    for (std::size_t k = 1; k <= num_face_blocks; ++k) {
        const std::string n = std::to_string(k);
        const std::string owner = "face block " + n;
        const std::string conn_name = "fbconn" + n;
        const std::size_t num_faces = file.length("num_fa_in_blk" + n);
        faces.push_back(num_faces);
        const std::optional<int> conn = file.var(conn_name);
        if (!conn) {
            if (num_faces > 0) {
                fail(ErrorCode::kParse,
                     "Exodus II " + owner + " has " + std::to_string(num_faces) +
                         " faces but no connectivity ('" + conn_name + "')",
                     file.where());
            }
            continue;
        }
        expect_element_type(file, *conn, owner, conn_name);
        if (file.var("fbepecnt" + n)) {
            // NSIDED: a face has at least 3 nodes.
            expect_counts_cover_list(file, owner, "fbepecnt" + n, "num_fa_in_blk" + n, conn_name,
                                     "num_nod_per_fa" + n, "face", "nodes", 3);
        } else {
            expect_shape(file, *conn, conn_name, {"num_fa_in_blk" + n, "num_nod_per_fa" + n});
        }
        expect_refs_in_range(file, owner, conn_name, "node", num_nodes, "the file's node count");
    }
    return faces;
}

// A polyhedral (NFACED) element block `b`: `ebepecnt<b>` gives each element's face count (at
// least 4), summing to the length of `facconn<b>`, whose face ids lie in the file's faces. VTK
// 9.1 finds a face's block with an off-by-one (the first face of every face block after the
// first is looked up past the end of the block before it), and it reads only NSIDED face blocks
// for polyhedra, so polyhedra must take their faces from one NSIDED face block.
void check_polyhedral_block(const NetcdfFile& file, std::size_t b,
                            const std::vector<std::size_t>& face_blocks) {
    const std::string n = std::to_string(b);
    const std::string owner = "element block " + n;
    if (face_blocks.size() != 1 || !file.var("fbepecnt1")) {
        fail(ErrorCode::kUnsupported,
             "Exodus II " + owner + " is polyhedral (NFACED) but the file has " +
                 std::to_string(face_blocks.size()) +
                 " face blocks: tetrender (through VTK 9.1) reads polyhedra whose faces are one "
                 "NSIDED face block",
             file.where());
    }
    expect_counts_cover_list(file, owner, "ebepecnt" + n, "num_el_in_blk" + n, "facconn" + n,
                             "num_fac_per_el" + n, "element", "faces", 4);
    expect_refs_in_range(file, owner, "facconn" + n, "face", face_blocks[0],
                         "the faces of face block 1");
}

// Every block and set the file counts must be one the Exodus library can describe: VTK's
// reader skips an object whose parameters it cannot read (ex_get_block, ex_get_set_param) but
// still counts it, and dereferences a null when it names the objects (GetSortedObjectInfo in
// BuildSIL; fuzz_exodus, second run: element block 2 had no num_el_in_blk2). An object whose
// status is not 0 (a null object) needs its size dimension. Costs one dimension look-up per
// object, at most one per byte of the file.
void check_object_sizes(const NetcdfFile& file, std::uintmax_t file_size) {
    struct Kind {
        const char* what;
        const char* count;
        const char* status;
        const char* size;
        const char* property;  // its properties: <property>1 (the ids), <property>2, ...
    };
    const Kind kinds[] = {
        {"element block", "num_el_blk", "eb_status", "num_el_in_blk", "eb_prop"},
        {"edge block", "num_ed_blk", "ed_status", "num_ed_in_blk", "ed_prop"},
        {"face block", "num_fa_blk", "fa_status", "num_fa_in_blk", "fa_prop"},
        {"node set", "num_node_sets", "ns_status", "num_nod_ns", "ns_prop"},
        {"side set", "num_side_sets", "ss_status", "num_side_ss", "ss_prop"},
        {"edge set", "num_edge_sets", "es_status", "num_edge_es", "es_prop"},
        {"face set", "num_face_sets", "fs_status", "num_face_fs", "fs_prop"},
        {"element set", "num_elem_sets", "els_status", "num_ele_els", "els_prop"}};
    // Each time step has its time stored in the file (at least 4 bytes): a fixed time_step of
    // 1073741824 in a small file made VTK's reader allocate until the system killed it (24 GB,
    // fuzz_exodus, 40).
    if (const std::size_t steps = file.length("time_step"); steps > file_size) {
        fail(ErrorCode::kParse,
             "Exodus II time_step = " + std::to_string(steps) + " is not plausible for a file of " +
                 std::to_string(file_size) + " bytes",
             file.where());
    }
    for (const Kind& kind : kinds) {
        const std::size_t count = file.length(kind.count);
        if (count == 0) continue;
        // Each object has at least an id stored in the file (4 bytes): a count beyond the file's
        // size is garbage (fuzz_exodus, fourth run: 1.1e9 element blocks).
        if (count > file_size) {
            fail(ErrorCode::kParse,
                 "Exodus II " + std::string(kind.count) + " = " + std::to_string(count) +
                     " is not plausible for a file of " + std::to_string(file_size) + " bytes",
                 file.where());
        }
        // The status of each object (1 when the file has none, as the library reads it).
        // A null object (status 0; the Exodus library writes 0 exactly when it is empty) that
        // has entries: VTK's reader skips it, then segfaults when a side set names its
        // elements (InsertSetSides) or polyhedra its faces (fuzz_exodus, eighth and ninth runs).
        const auto expect_size = [&](std::size_t i, long long status) {
            const std::string size = kind.size + std::to_string(i + 1);
            if (status != 0 && !file.dim(size)) {
                fail(ErrorCode::kParse,
                     "Exodus II " + std::string(kind.what) + " " + std::to_string(i + 1) +
                         " has no size ('" + size + "') and is not a null " + kind.what + " (" +
                         kind.status + " " + std::to_string(status) + ")",
                     file.where());
            }
            if (const std::size_t entries = file.length(size); status == 0 && entries > 0) {
                fail(ErrorCode::kParse,
                     "Exodus II " + std::string(kind.what) + " " + std::to_string(i + 1) +
                         " is a null " + kind.what + " (" + kind.status + " 0) but has " +
                         std::to_string(entries) + " entries ('" + size + "')",
                     file.where());
            }
        };
        if (const std::optional<int> v = file.var(kind.status)) {
            expect_shape(file, *v, kind.status, {kind.count});
            file.for_each_value(*v, kind.status, expect_size);
        } else {
            for (std::size_t i = 0; i < count; ++i) expect_size(i, 1);
        }
        // A property holds one value an object: ids over another dimension (one id for two
        // blocks) left VTK's reader naming a block it had skipped (SEGV in
        // GetSortedObjectInfo, fuzz_exodus, twelfth run).
        for (int k = 1;; ++k) {
            const std::string name = kind.property + std::to_string(k);
            const std::optional<int> v = file.var(name);
            if (!v) break;
            expect_shape(file, *v, name, {kind.count});
        }
    }
}

// Result variables need their names: VTK's reader gives the Exodus library name buffers of its
// own (malloc'd, not cleared) and runs strlen over them (RemoveBeginningAndTrailingSpaces); when
// a count of variables (num_nod_var, ...) has no names variable, the library warns and leaves
// them untouched, and VTK reads past their end (fuzz_exodus, first run: ASan heap-buffer-
// overflow; silent in a normal build). Measured under ASan for nodal, element and global
// variables; names that are not text, shorter rows or fewer rows than the count are no fault:
// VTK then says 'Could not read nodal variable names.'.
void check_result_variable_names(const NetcdfFile& file) {
    for (const char* kind :
         {"glo", "nod", "elem", "edge", "face", "nset", "eset", "fset", "sset", "elset"}) {
        const std::string count_dim = std::string("num_") + kind + "_var";
        const std::string names = std::string("name_") + kind + "_var";
        const std::size_t count = file.length(count_dim);
        if (count > 0 && !file.var(names)) {
            fail(ErrorCode::kParse,
                 "Exodus II: '" + count_dim + "' is " + std::to_string(count) +
                     " but the file has no '" + names + "' (their names)",
                 file.where());
        }
    }
}

// Block `b` (1-based): its connectivity refers to nodes 1..num_nodes, its shape matches its
// counts; returns its element count.
std::size_t check_block(const NetcdfFile& file, std::size_t b, std::size_t num_nodes,
                        const std::vector<std::size_t>& face_blocks) {
    const std::string n = std::to_string(b);
    const std::string conn_name = "connect" + n;
    const std::string block = "element block " + n;
    const std::optional<int> conn = file.var(conn_name);
    const std::size_t num_elems = file.length("num_el_in_blk" + n);
    if (!conn) {
        // Polyhedra list faces (facconn<b>), not nodes.
        if (const std::optional<int> faces = file.var("facconn" + n)) {
            if (file.upper_text_attribute(*faces, "elem_type").rfind("NFACED", 0) != 0) {
                fail(ErrorCode::kParse,
                     "Exodus II " + block + " has faces ('facconn" + n +
                         "') but no node connectivity ('" + conn_name + "') and is not NFACED",
                     file.where());
            }
            check_polyhedral_block(file, b, face_blocks);
            return num_elems;
        }
        if (num_elems > 0) {
            fail(ErrorCode::kParse,
                 "Exodus II " + block + " has " + std::to_string(num_elems) +
                     " elements but no connectivity ('" + conn_name + "')",
                 file.where());
        }
        return 0;
    }
    expect_element_type(file, *conn, block, conn_name);
    if (file.var("ebepecnt" + n)) {
        // N-sided block: one node count per element, summing to the list length.
        expect_counts_cover_list(file, block, "ebepecnt" + n, "num_el_in_blk" + n, conn_name,
                                 "num_nod_per_el" + n, "element", "nodes", 1);
    } else {
        expect_shape(file, *conn, conn_name, {"num_el_in_blk" + n, "num_nod_per_el" + n});
        expect_nodes_for_type(file, *conn, block, conn_name, file.length("num_nod_per_el" + n),
                              "num_nod_per_el" + n);
    }
    const std::size_t per_element = std::max<std::size_t>(1, file.length("num_nod_per_el" + n));
    file.for_each_value(*conn, conn_name, [&](std::size_t i, long long v) {
        if (v < 1 || static_cast<unsigned long long>(v) > num_nodes) {
            fail(ErrorCode::kParse,
                 "Exodus II " + block + " (" + conn_name + "): element " +
                     std::to_string(i / per_element + 1) + " refers to node " + std::to_string(v) +
                     ", outside 1.." + std::to_string(num_nodes) + " (the file's node count)",
                 file.where());
        }
    });
    return num_elems;
}

}  // namespace

// The global attributes the Exodus library's ex_open reads after opening the file: without a
// 'version' of at least 2.0 and a floating-point word size of 4 or 8 it gives up without
// closing the netCDF file, so each such file read left a descriptor and the library's state
// behind (fuzz_exodus, finding 38: a few hundred of them in one process crashed VTK's reader).
std::string short_number(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", value);
    return text;
}

void check_global_attributes(const NetcdfFile& file) {
    const std::optional<double> version = file.global_number("version");
    if (!version) {
        fail(ErrorCode::kParse, "Exodus II: the global attribute 'version' (a number) is missing",
             file.where());
    }
    if (!(*version >= 2.0) || !std::isfinite(*version)) {
        fail(ErrorCode::kUnsupported,
             "Exodus II: version " + short_number(*version) +
                 " (the global attribute 'version'); files before version 2.0 are not read",
             file.where());
    }
    // The names' buffers are this long: 1128547840 made VTK's reader take 8.8 GB and 29 s
    // (fuzz_exodus, 39), and 0 left them one byte that the library filled without a
    // terminator (ASan: strlen past it in RequestInformation, fuzz_exodus, 47). The Exodus
    // library allows at most NC_MAX_NAME (256).
    if (const std::optional<double> length = file.global_number("maximum_name_length");
        length && !(*length >= 1 && *length <= NC_MAX_NAME)) {
        fail(ErrorCode::kParse,
             "Exodus II: 'maximum_name_length' is " + short_number(*length) + ", not 1 to " +
                 std::to_string(NC_MAX_NAME),
             file.where());
    }
    std::optional<double> word_size = file.global_number("floating_point_word_size");
    if (!word_size) word_size = file.global_number("floating point word size");  // before 2.02
    if (!word_size) {
        fail(ErrorCode::kParse,
             "Exodus II: the global attribute 'floating_point_word_size' (4 or 8) is missing",
             file.where());
    }
    if (*word_size != 4 && *word_size != 8) {
        fail(
            ErrorCode::kParse,
            "Exodus II: 'floating_point_word_size' is " + short_number(*word_size) + ", not 4 or 8",
            file.where());
    }
}

void check_exodus_contents(const fs::path& path) {
    const NetcdfFile file(path);
    check_global_attributes(file);
    // VTK's reader keeps three coordinates a node: a larger num_dim corrupted its heap (a
    // 'double free or corruption' abort reading one file, and crashes later in the process).
    const std::optional<int> num_dim = file.dim("num_dim");
    if (!num_dim) {
        fail(ErrorCode::kParse, "Exodus II: the dimension 'num_dim' is missing", file.where());
    }
    if (const std::size_t n = file.dim_length(*num_dim); n < 1 || n > 3) {
        fail(ErrorCode::kParse,
             "Exodus II: num_dim is " + std::to_string(n) + "; a mesh has 1, 2 or 3 dimensions",
             file.where());
    }
    const std::size_t num_nodes = file.length("num_nodes");
    const std::size_t num_elem = file.length("num_elem");
    const std::size_t num_blocks = file.length("num_el_blk");

    // Coordinates: one array per axis, or one (num_dim, num_nodes) array.
    for (const char* axis : {"coordx", "coordy", "coordz"}) {
        if (const std::optional<int> v = file.var(axis)) {
            expect_shape(file, *v, axis, {"num_nodes"});
        }
    }
    if (const std::optional<int> v = file.var("coord")) {
        expect_shape(file, *v, "coord", {"num_dim", "num_nodes"});
    } else if (num_nodes > 0) {
        // Without them VTK's reader went on and dereferenced a null array (GetCacheOrRead;
        // fuzz_exodus, fourteenth run, where num_dim, stored as a second record dimension,
        // read as 1).
        const std::size_t dims = file.dim_length(*num_dim);
        const char* axes[] = {"coordx", "coordy", "coordz"};
        for (std::size_t a = 0; a < dims; ++a) {
            if (!file.var(axes[a])) {
                fail(ErrorCode::kParse,
                     std::string("Exodus II: the node coordinates '") + axes[a] +
                         "' are missing (and there is no 'coord')",
                     file.where());
            }
        }
    }
    for (const char* map : {"node_num_map", "node_id_map"}) {
        if (const std::optional<int> v = file.var(map)) expect_shape(file, *v, map, {"num_nodes"});
    }
    for (const char* map : {"elem_num_map", "elem_id_map"}) {
        if (const std::optional<int> v = file.var(map)) expect_shape(file, *v, map, {"num_elem"});
    }

    check_object_sizes(file, fs::file_size(path));
    check_result_variable_names(file);
    const std::vector<std::size_t> face_blocks = check_face_blocks(file, num_nodes);
    std::size_t total = 0;
    for (std::size_t b = 1; b <= num_blocks; ++b) {
        const std::size_t n = check_block(file, b, num_nodes, face_blocks);
        if (n > num_elem - std::min(total, num_elem)) {
            fail(ErrorCode::kParse,
                 "Exodus II element blocks hold more elements than num_elem (" +
                     std::to_string(num_elem) + ")",
                 file.where());
        }
        total += n;
    }

    // Result variables: one value per node or per element of their block, per time step.
    const std::size_t num_nod_var = file.length("num_nod_var");
    for (std::size_t v = 1; v <= num_nod_var; ++v) {
        const std::string name = "vals_nod_var" + std::to_string(v);
        if (const std::optional<int> id = file.var(name)) {
            expect_shape(file, *id, name, {"time_step", "num_nodes"});
        }
    }
    if (const std::optional<int> id = file.var("vals_nod_var")) {
        expect_shape(file, *id, "vals_nod_var", {"time_step", "num_nod_var", "num_nodes"});
    }
    const std::size_t num_elem_var = file.length("num_elem_var");
    for (std::size_t v = 1; v <= num_elem_var; ++v) {
        for (std::size_t b = 1; b <= num_blocks; ++b) {
            const std::string name = "vals_elem_var" + std::to_string(v) + "eb" + std::to_string(b);
            if (const std::optional<int> id = file.var(name)) {
                expect_shape(file, *id, name, {"time_step", "num_el_in_blk" + std::to_string(b)});
            }
        }
    }

    // Side sets name elements (1..num_elem) and a side of each (a 3-D element has at most 6,
    // its type's own count: sides_of_type); node sets name nodes.
    const std::size_t num_side_sets = file.length("num_side_sets");
    struct BlockSides {
        std::size_t end = 0;  // one past its last element (1-based numbering: its last)
        int sides = 6;
        std::string type;
    };
    std::vector<BlockSides> block_sides;
    if (num_side_sets > 0) {
        std::size_t end = 0;
        for (std::size_t b = 1; b <= num_blocks; ++b) {
            const std::string n = std::to_string(b);
            end += file.length("num_el_in_blk" + n);
            BlockSides block{end, 6, ""};
            if (const std::optional<int> conn = file.var("connect" + n)) {
                block.type = element_type(file, *conn);
                block.sides = sides_of_type(block.type);
            }
            block_sides.push_back(block);
        }
    }
    for (std::size_t s = 1; s <= num_side_sets; ++s) {
        const std::string n = std::to_string(s);
        for (const char* var : {"elem_ss", "side_ss"}) {
            if (const std::optional<int> id = file.var(var + n)) {
                expect_shape(file, *id, var + n, {"num_side_ss" + n});
            }
        }
        expect_ids_in_range(file, "elem_ss" + n, "side set " + n, num_elem,
                            "the file's element count");
        expect_ids_in_range(file, "side_ss" + n, "side set " + n, 6, "an element's sides");
        const std::optional<int> elems = file.var("elem_ss" + n);
        const std::optional<int> sides = file.var("side_ss" + n);
        if (!elems || !sides) continue;
        std::vector<long long> elem_ids;
        file.for_each_value(*elems, "elem_ss" + n,
                            [&](std::size_t, long long v) { elem_ids.push_back(v); });
        file.for_each_value(*sides, "side_ss" + n, [&](std::size_t i, long long side) {
            if (i >= elem_ids.size()) return;
            const auto e = static_cast<std::size_t>(elem_ids[i]);  // in 1..num_elem (above)
            const auto block = std::upper_bound(
                block_sides.begin(), block_sides.end(), e - 1,
                [](std::size_t index, const BlockSides& b) { return index < b.end; });
            if (block == block_sides.end() || side <= block->sides) return;
            fail(ErrorCode::kParse,
                 "Exodus II side set " + n + " (side_ss" + n + "): entry " + std::to_string(i) +
                     " names side " + std::to_string(side) + " of element " + std::to_string(e) +
                     ", a " + block->type + " of element block " +
                     std::to_string(block - block_sides.begin() + 1) + ", which has " +
                     std::to_string(block->sides) + " sides",
                 file.where());
        });
    }
    const std::size_t num_node_sets = file.length("num_node_sets");
    for (std::size_t s = 1; s <= num_node_sets; ++s) {
        const std::string n = std::to_string(s);
        expect_ids_in_range(file, "node_ns" + n, "node set " + n, num_nodes,
                            "the file's node count");
    }
}

}  // namespace tr::io_detail
