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
