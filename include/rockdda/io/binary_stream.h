/**
 * @file
 * Raw binary writing and bounds-checked
 * reading of plain values for checkpoints (exact doubles, so that a resumed
 * run continues bit for bit).
 */
#ifndef ROCKDDA_IO_BINARY_STREAM_H
#define ROCKDDA_IO_BINARY_STREAM_H

#include <rockdda/io/error.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace rockdda::io
{
  /// Appends plain values to a byte string.
  class BinaryWriter
  {
  public:
    template <typename T>
    void
    put(const T &value)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      bytes.append(reinterpret_cast<const char *>(&value), sizeof(T));
    }

    void
    put_string(const std::string &s)
    {
      put<std::uint64_t>(s.size());
      bytes += s;
    }

    /// A sequence of doubles (count, then values).
    template <typename Sequence>
    void
    put_doubles(const Sequence &values)
    {
      put<std::uint64_t>(values.size());
      for (const double v : values)
        put(v);
    }

    /// The values of a fixed-size vector (Eigen, std::array) as doubles,
    /// without a count (the reader knows the size).
    template <typename Vector>
    void
    put_fixed(const Vector &v)
    {
      for (int i = 0; i < static_cast<int>(v.size()); ++i)
        put<double>(v[i]);
    }

    /// The header of a checkpoint: its kind (@p magic) and format version.
    void
    put_header(const std::string &magic, const std::uint32_t version)
    {
      put_string(magic);
      put(version);
    }

    /// The bytes written so far.
    std::string bytes;
  };

  /// Reads plain values from a byte string; throws InputError naming
  /// @p source if the data end early.
  class BinaryReader
  {
  public:
    BinaryReader(const std::string &bytes, const std::string &source)
        : bytes(bytes)
        , source(source)
    {}

    template <typename T>
    T
    get()
    {
      static_assert(std::is_trivially_copyable_v<T>);
      require(sizeof(T));
      T value;
      std::memcpy(&value, bytes.data() + position, sizeof(T));
      position += sizeof(T);
      return value;
    }

    std::string
    get_string()
    {
      const auto n = get<std::uint64_t>();
      require(n);
      std::string s = bytes.substr(position, n);
      position += n;
      return s;
    }

    /// A sequence of doubles written by put_doubles().
    std::vector<double>
    get_doubles()
    {
      const auto n = get<std::uint64_t>();
      if (n > (bytes.size() - position) / sizeof(double))
        require(bytes.size() - position + 1); // throws: truncated
      std::vector<double> values(n);
      for (double &v : values)
        v = get<double>();
      return values;
    }

    /// Read a vector written by BinaryWriter::put_fixed() into @p v.
    template <typename Vector>
    void
    get_fixed(Vector &v)
    {
      for (int i = 0; i < static_cast<int>(v.size()); ++i)
        v[i] = get<double>();
    }

    /// The same, returning a fixed-size vector of type @p Vector.
    template <typename Vector>
    Vector
    get_fixed()
    {
      Vector v;
      get_fixed(v);
      return v;
    }

    /// Read and check a header written by BinaryWriter::put_header();
    /// throws InputError naming the source if the kind or the version
    /// differ.
    void
    check_header(const std::string &magic, const std::uint32_t version)
    {
      if (get_string() != magic)
        throw InputError(source + ": not a " + magic);
      const auto v = get<std::uint32_t>();
      if (v != version)
        throw InputError(source + ": checkpoint format " + std::to_string(v)
                         + "; this build reads format "
                         + std::to_string(version));
    }

    /// Read a count and check it against the scene's @p expected; throws
    /// InputError ("it belongs to another scene") if they differ.
    void
    expect_count(const std::size_t expected, const std::string &what)
    {
      const auto n = get<std::uint64_t>();
      if (n != expected)
        throw InputError(source + ": the checkpoint has " + std::to_string(n)
                         + " " + what + ", the scene "
                         + std::to_string(expected)
                         + ": it belongs to another scene");
    }

    /// Read the count of a list whose items take at least @p bytes_each
    /// bytes; throws InputError (damaged) if the rest of the data cannot
    /// hold them.
    std::uint64_t
    get_count(const std::size_t bytes_each, const std::string &what)
    {
      const auto n = get<std::uint64_t>();
      if (n > (bytes.size() - position) / bytes_each)
        throw InputError(source + ": the checkpoint is damaged ("
                         + std::to_string(n) + " " + what + " in "
                         + std::to_string(bytes.size()) + " bytes)");
      return n;
    }

    /// An int32 in [0, @p max] (an enumeration); throws InputError
    /// (damaged, naming @p what) otherwise.
    std::int32_t
    get_index(const std::int32_t max, const std::string &what)
    {
      const auto i = get<std::int32_t>();
      if (i < 0 || i > max)
        throw InputError(source + ": the checkpoint is damaged (" + what + " "
                         + std::to_string(i) + ")");
      return i;
    }

    /// True if every byte has been read.
    bool
    at_end() const
    {
      return position == bytes.size();
    }

  private:
    void
    require(const std::uint64_t n) const
    {
      if (n > bytes.size() - position)
        throw InputError(source + ": the checkpoint is truncated (needs "
                         + std::to_string(n) + " more bytes at byte "
                         + std::to_string(position) + " of "
                         + std::to_string(bytes.size()) + ")");
    }

    const std::string &bytes;
    std::string        source;
    std::size_t        position = 0;
  };
} // namespace rockdda::io

#endif
