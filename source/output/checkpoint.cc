// The layout of checkpoint.bin (host byte order; a byte-order mark refuses a foreign one):
//   "RITRCKPT", u32 format version, u32 0x01020304, u64 payload size, payload, u64 FNV-1a
//   of the payload.
// The payload lists the fields of Checkpoint in declaration order; a vector or list is a
// u64 count followed by its items, a string a u64 length followed by its bytes.
#include <ritr/common/atomic_file.h>
#include <ritr/common/input_error.h>
#include <ritr/output/checkpoint.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <type_traits>

namespace ritr
{
  namespace
  {
    constexpr char          magic[8]   = {'R', 'I', 'T', 'R', 'C', 'K', 'P', 'T'};
    // 2: steps carry the outer stop; 3: the barrier stiffness; 4: the final energy terms;
    // 5: the stepper's carried state; 6: the scene's entries (last), the fingerprint of only
    // those set away from their defaults
    constexpr std::uint32_t version    = 6;
    constexpr std::uint32_t byte_order = 0x01020304;
    constexpr std::size_t   header_size = sizeof(magic) + 2 * sizeof(std::uint32_t) + sizeof(std::uint64_t);

    class Writer
    {
    public:
      template <typename T>
      void put(const T &value)
      {
        static_assert(std::is_arithmetic_v<T>);
        bytes.append(reinterpret_cast<const char *>(&value), sizeof(T));
      }
      void put(const Eigen::VectorXd &v)
      {
        put<std::uint64_t>(v.size());
        bytes.append(reinterpret_cast<const char *>(v.data()), v.size() * sizeof(double));
      }
      void put(const std::string &s)
      {
        put<std::uint64_t>(s.size());
        bytes += s;
      }

      std::string bytes;
    };

    // Reads the payload; running past its end means the counts inside it are wrong.
    class Reader
    {
    public:
      Reader(const std::string &bytes, const std::string &path) : bytes_(bytes), path_(path) {}

      template <typename T>
      T get()
      {
        static_assert(std::is_arithmetic_v<T>);
        T value;
        std::memcpy(&value, take(sizeof(T)), sizeof(T));
        return value;
      }
      std::uint64_t count(const std::size_t item_size)
      {
        const auto n = get<std::uint64_t>();
        if (n > (bytes_.size() - position_) / item_size)
          corrupted();
        return n;
      }
      Eigen::VectorXd vector()
      {
        Eigen::VectorXd v(count(sizeof(double)));
        std::memcpy(v.data(), take(v.size() * sizeof(double)), v.size() * sizeof(double));
        return v;
      }
      std::string string()
      {
        const auto n = count(1);
        return std::string(take(n), n);
      }
      bool at_end() const { return position_ == bytes_.size(); }
      [[noreturn]] void corrupted() const
      {
        throw InputError(path_ + ": is corrupted (its contents do not match its layout)");
      }

    private:
      const char *take(const std::size_t n)
      {
        if (n > bytes_.size() - position_)
          corrupted();
        const char *p = bytes_.data() + position_;
        position_ += n;
        return p;
      }

      const std::string &bytes_;
      const std::string &path_;
      std::size_t        position_ = 0;
    };

    void put_report(Writer &w, const StepReport &r)
    {
      w.put<std::uint32_t>(r.step);
      w.put(r.time);
      w.put(r.energy);
      w.put<std::uint32_t>(r.newton_iterations);
      w.put<std::uint32_t>(r.outer_iterations);
      w.put<std::uint32_t>(r.line_search_trials);
      for (const double q : {r.initial_objective, r.sliding_violation, r.inner_seconds, r.transfer_seconds,
                             r.outer_solve_seconds, r.min_distance, r.min_reference_measure,
                             r.min_deformed_jacobian, r.wall_seconds})
        w.put(q);
      w.put<std::uint32_t>(r.outer_stop ? 1 + static_cast<std::uint32_t>(*r.outer_stop) : 0);  // 0: fixed mesh
    }

    StepReport get_report(Reader &in)
    {
      StepReport r;
      r.step               = in.get<std::uint32_t>();
      r.time               = in.get<double>();
      r.energy             = in.get<double>();
      r.newton_iterations  = in.get<std::uint32_t>();
      r.outer_iterations   = in.get<std::uint32_t>();
      r.line_search_trials = in.get<std::uint32_t>();
      for (double *q : {&r.initial_objective, &r.sliding_violation, &r.inner_seconds, &r.transfer_seconds,
                        &r.outer_solve_seconds, &r.min_distance, &r.min_reference_measure,
                        &r.min_deformed_jacobian, &r.wall_seconds})
        *q = in.get<double>();
      if (const auto stop = in.get<std::uint32_t>(); stop > 0)
        r.outer_stop = static_cast<OuterStop>(stop - 1);
      return r;
    }

    constexpr std::size_t report_size = 5 * sizeof(std::uint32_t) + 11 * sizeof(double);

    // What a checksum cannot catch: contents that no run writes ("" when there is none).
    std::string implausible_contents(const Checkpoint &c)
    {
      for (const Eigen::VectorXd *v : {&c.u, &c.x, &c.v, &c.obstacle_positions})
        if (!v->allFinite())
          return "its state is not finite";
      if (!std::isfinite(c.time) || c.time < 0)
        return "its time is not a finite time";
      if (!(c.barrier_stiffness >= 0) || !std::isfinite(c.barrier_stiffness))
        return "its barrier stiffness is not finite";
      double previous = 0;
      for (std::size_t i = 0; i < c.history.size(); ++i)
        {
          const StepReport &r = c.history[i];
          if (r.step != i + 1 || !(r.time >= previous) || !std::isfinite(r.time))
            return "its step reports are out of order";
          previous = r.time;
        }
      if (c.time != previous)
        return "its time is not its last step's";
      return "";
    }
  } // namespace

  std::uint64_t fnv1a(const void *data, const std::size_t bytes, std::uint64_t hash)
  {
    const auto *p = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < bytes; ++i)
      hash = (hash ^ p[i]) * 1099511628211ull;
    return hash;
  }

  void write_checkpoint(const std::string &path, const Checkpoint &c)
  {
    Writer payload;
    payload.put<std::uint32_t>(c.dimension);
    payload.put<std::uint64_t>(c.scene_hash);
    payload.put<std::uint32_t>(c.step);
    payload.put(c.time);
    for (const Eigen::VectorXd *v : {&c.u, &c.x, &c.v, &c.obstacle_positions})
      payload.put(*v);
    payload.put(c.barrier_stiffness);
    payload.put<std::uint64_t>(c.history.size());
    for (const auto &r : c.history)
      put_report(payload, r);
    payload.put<std::uint64_t>(c.invariant_violations.size());
    for (const auto &s : c.invariant_violations)
      payload.put(s);
    payload.put(c.wall_seconds);
    payload.put(c.output_seconds);
    payload.put(c.linear_solve_seconds);
    payload.put<std::uint64_t>(c.symbolic_factorizations);
    payload.put<std::uint64_t>(c.numeric_factorizations);
    payload.put<std::uint64_t>(c.final_energy_terms.size());
    for (const auto &[name, value] : c.final_energy_terms)
      {
        payload.put(name);
        payload.put(value);
      }
    payload.put(c.stepper_state);
    payload.put(c.scene_entries);

    Writer file;
    file.bytes.append(magic, sizeof(magic));
    file.put(version);
    file.put(byte_order);
    file.put<std::uint64_t>(payload.bytes.size());
    file.bytes += payload.bytes;
    file.put<std::uint64_t>(fnv1a(payload.bytes.data(), payload.bytes.size()));
    write_file_atomically(path, [&](std::ostream &out) { out.write(file.bytes.data(), file.bytes.size()); });
  }

  InputError no_checkpoint_error(const std::string &path)
  {
    return InputError(path + ": no checkpoint to resume from (run the scene without --resume to start it)");
  }

  Checkpoint read_checkpoint(const std::string &path)
  {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
      throw no_checkpoint_error(path);
    std::ifstream in(path, std::ios::binary);
    if (!in || !std::filesystem::is_regular_file(path, ec))
      throw InputError(path + ": cannot be read");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad())
      throw InputError(path + ": cannot be read");
    if (bytes.size() < sizeof(magic) || std::memcmp(bytes.data(), magic, sizeof(magic)) != 0)
      throw InputError(path + ": is not a ritr checkpoint");
    const auto truncated = [&](const std::size_t expected) {
      return InputError(path + ": is truncated (" + std::to_string(bytes.size()) + " of " +
                        std::to_string(expected) + " bytes)");
    };
    if (bytes.size() < header_size)
      throw truncated(header_size);
    Reader header(bytes, path);
    for (std::size_t i = 0; i < sizeof(magic); ++i)
      header.get<char>();
    const auto file_version = header.get<std::uint32_t>();
    if (header.get<std::uint32_t>() != byte_order)
      throw InputError(path + ": was written on a machine of another byte order");
    if (file_version != version)
      throw InputError(path + ": has format version " + std::to_string(file_version) + ", this ritr reads version " +
                       std::to_string(version));
    const auto payload_size = header.get<std::uint64_t>();
    if (payload_size > bytes.size())
      throw truncated(header_size + payload_size + sizeof(std::uint64_t));
    const std::size_t expected = header_size + payload_size + sizeof(std::uint64_t);
    if (bytes.size() < expected)
      throw truncated(expected);
    if (bytes.size() > expected)
      throw InputError(path + ": is corrupted (" + std::to_string(bytes.size() - expected) +
                       " bytes after its end)");
    const std::string payload = bytes.substr(header_size, payload_size);
    std::uint64_t     checksum;
    std::memcpy(&checksum, bytes.data() + header_size + payload_size, sizeof(checksum));
    if (checksum != fnv1a(payload.data(), payload.size()))
      throw InputError(path + ": is corrupted (checksum mismatch)");

    Reader     r(payload, path);
    Checkpoint c;
    c.dimension  = r.get<std::uint32_t>();
    c.scene_hash = r.get<std::uint64_t>();
    c.step       = r.get<std::uint32_t>();
    c.time       = r.get<double>();
    for (Eigen::VectorXd *v : {&c.u, &c.x, &c.v, &c.obstacle_positions})
      *v = r.vector();
    c.barrier_stiffness = r.get<double>();
    c.history.resize(r.count(report_size));
    for (auto &report : c.history)
      report = get_report(r);
    c.invariant_violations.resize(r.count(sizeof(std::uint64_t)));
    for (auto &s : c.invariant_violations)
      s = r.string();
    c.wall_seconds            = r.get<double>();
    c.output_seconds          = r.get<double>();
    c.linear_solve_seconds    = r.get<double>();
    c.symbolic_factorizations = r.get<std::uint64_t>();
    c.numeric_factorizations  = r.get<std::uint64_t>();
    c.final_energy_terms.resize(r.count(sizeof(std::uint64_t) + sizeof(double)));
    for (auto &[name, value] : c.final_energy_terms)
      {
        name  = r.string();
        value = r.get<double>();
      }
    c.stepper_state = r.vector();
    c.scene_entries = r.string();
    if (!r.at_end())
      r.corrupted();
    if (const std::string problem = implausible_contents(c); !problem.empty())
      throw InputError(path + ": is corrupted (" + problem + ")");
    return c;
  }
} // namespace ritr
