#include <mesh/copyleft/detail/tetgen_wire.h>

#include <cstddef>
#include <cstring>
#include <type_traits>

namespace tr::detail {
namespace {

constexpr std::uint32_t kRequestMagic = 0x47544652;  // "RFTG"
constexpr std::uint32_t kAnswerMagic = 0x47544641;   // "AFTG"

class Writer {
  public:
    template <typename T>
    void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        const char* p = reinterpret_cast<const char*>(&value);
        bytes_.insert(bytes_.end(), p, p + sizeof(T));
    }
    template <typename T>
    void put_array(const std::vector<T>& values) {
        static_assert(std::is_trivially_copyable_v<T>);
        put(static_cast<std::uint64_t>(values.size()));
        const char* p = reinterpret_cast<const char*>(values.data());
        bytes_.insert(bytes_.end(), p, p + values.size() * sizeof(T));
    }
    void put_string(const std::string& text) {
        put(static_cast<std::uint64_t>(text.size()));
        bytes_.insert(bytes_.end(), text.begin(), text.end());
    }
    std::vector<char> take() { return std::move(bytes_); }

  private:
    std::vector<char> bytes_;
};

// Reads what Writer wrote; every read checks the bytes left, and a failed read leaves ok() false.
class Reader {
  public:
    explicit Reader(const std::vector<char>& bytes) : bytes_(bytes) {}
    template <typename T>
    bool get(T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        if (!ok_ || bytes_.size() - at_ < sizeof(T)) return ok_ = false;
        std::memcpy(&value, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return true;
    }
    template <typename T>
    bool get_array(std::vector<T>& values) {
        std::uint64_t size = 0;
        if (!get(size) || size > (bytes_.size() - at_) / sizeof(T)) return ok_ = false;
        values.resize(size);
        if (size > 0) std::memcpy(values.data(), bytes_.data() + at_, size * sizeof(T));
        at_ += size * sizeof(T);
        return true;
    }
    bool get_string(std::string& text) {
        std::vector<char> chars;
        if (!get_array(chars)) return false;
        text.assign(chars.begin(), chars.end());
        return true;
    }
    bool ok() const { return ok_; }
    bool at_end() const { return ok_ && at_ == bytes_.size(); }

  private:
    const std::vector<char>& bytes_;
    std::size_t at_ = 0;
    bool ok_ = true;
};

}  // namespace

std::vector<char> encode_request(const TetgenRequest& request) {
    Writer out;
    out.put(kRequestMagic);
    out.put_string(request.switches);
    const TetgenPlc& plc = request.plc;
    out.put_array(plc.points);
    out.put_array(plc.triangles);
    out.put_array(plc.quads);
    out.put_array(plc.holes);
    out.put(static_cast<std::uint64_t>(plc.facets.size()));
    for (const TetgenFacet& facet : plc.facets) {
        out.put(static_cast<std::uint64_t>(facet.polygons.size()));
        for (const auto& polygon : facet.polygons) out.put_array(polygon);
        out.put_array(facet.holes);
    }
    return out.take();
}

Result<TetgenRequest> decode_request(const std::vector<char>& bytes) {
    Reader in(bytes);
    TetgenRequest request;
    TetgenPlc& plc = request.plc;
    std::uint32_t magic = 0;
    std::uint64_t num_facets = 0;
    const bool head_ok = in.get(magic) && magic == kRequestMagic &&
                         in.get_string(request.switches) && in.get_array(plc.points) &&
                         in.get_array(plc.triangles) && in.get_array(plc.quads) &&
                         in.get_array(plc.holes) && in.get(num_facets) &&
                         num_facets <= bytes.size();  // each facet takes bytes
    if (!head_ok) return make_error(ErrorCode::kInternal, "malformed TetGen request");
    plc.facets.resize(num_facets);
    for (TetgenFacet& facet : plc.facets) {
        std::uint64_t num_polygons = 0;
        if (!in.get(num_polygons) || num_polygons > bytes.size()) break;
        facet.polygons.resize(num_polygons);
        for (auto& polygon : facet.polygons) {
            if (!in.get_array(polygon)) break;
        }
        if (!in.get_array(facet.holes)) break;
    }
    if (!in.at_end()) return make_error(ErrorCode::kInternal, "malformed TetGen request");
    return request;
}

std::vector<char> encode_answer(const TetgenAnswer& answer) {
    Writer out;
    out.put(kAnswerMagic);
    out.put(answer.outcome);
    out.put(answer.code);
    out.put_string(answer.text);
    out.put_array(answer.result.points);
    out.put_array(answer.result.tets);
    return out.take();
}

Result<TetgenAnswer> decode_answer(const std::vector<char>& bytes) {
    Reader in(bytes);
    TetgenAnswer answer;
    std::uint32_t magic = 0;
    const bool ok = in.get(magic) && magic == kAnswerMagic && in.get(answer.outcome) &&
                    in.get(answer.code) && in.get_string(answer.text) &&
                    in.get_array(answer.result.points) && in.get_array(answer.result.tets) &&
                    in.at_end();
    if (!ok) {
        return make_error(ErrorCode::kInternal, "TetGen's process ended without a full answer");
    }
    return answer;
}

}  // namespace tr::detail
