/**
 * @file
 * A small reader of VTK XML unstructured-grid files with binary (base64)
 * DataArrays, zlib-compressed or not, header_type UInt32 (the default) or
 * UInt64: what rockdda's DDA output (vtu_output.cc) and deal.II's
 * DataOut::write_vtu (heat) write. For the tests only: the arrays of one
 * piece, by name.
 */
#ifndef ROCKDDA_TESTS_UNIT_VTU_READER_H
#define ROCKDDA_TESTS_UNIT_VTU_READER_H

#include <deal.II/base/config.h>

#include <gtest/gtest.h>

#ifdef DEAL_II_WITH_ZLIB
#  include <zlib.h>
#endif

#include <cstdint>
#include <cstring>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace rockdda::test
{
  /// Bytes of base64 text (no line breaks inside).
  inline std::string
  base64_decode(const std::string &text)
  {
    auto value = [](const char c) -> int {
      if (c >= 'A' && c <= 'Z')
        return c - 'A';
      if (c >= 'a' && c <= 'z')
        return c - 'a' + 26;
      if (c >= '0' && c <= '9')
        return c - '0' + 52;
      if (c == '+')
        return 62;
      if (c == '/')
        return 63;
      return -1;
    };
    EXPECT_EQ(text.size() % 4, 0u);
    std::string out;
    for (std::size_t i = 0; i + 4 <= text.size(); i += 4)
      {
        std::uint32_t w = 0;
        int           n = 0;
        for (int k = 0; k < 4; ++k)
          {
            const int v = text[i + k] == '=' ? 0 : value(text[i + k]);
            EXPECT_GE(v, 0) << "not base64: " << text[i + k];
            w = (w << 6) | static_cast<std::uint32_t>(v);
            n += text[i + k] != '=';
          }
        for (int k = 0; k < n - 1; ++k)
          out += static_cast<char>((w >> (16 - 8 * k)) & 255);
      }
    return out;
  }

  /// One DataArray read back.
  struct Array
  {
    std::string                        type;
    int                                components = 1;
    std::map<std::string, std::string> attributes;
    std::string                        bytes;

    template <typename T>
    std::vector<T>
    values() const
    {
      std::vector<T> v(bytes.size() / sizeof(T));
      std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
      return v;
    }
  };

  /// A VTU file: its DataArrays by name ("Points" for the points).
  /// Binary arrays are decoded; the attribute format says which.
  struct Vtu
  {
    std::string                  text;
    bool                         compressed = false;
    std::size_t                  word       = 4; ///< bytes of a header entry
    std::map<std::string, Array> arrays;

    explicit Vtu(const std::string &t)
        : text(t)
    {
      compressed = text.find("compressor=\"vtkZLibDataCompressor\"")
                   != std::string::npos;
      if (text.find("header_type=\"UInt64\"") != std::string::npos)
        word = 8;
      const std::regex element(
        "<DataArray([^>]*)>\\s*([^<]*?)\\s*</DataArray>");
      const std::regex attribute("(\\w+)=\"([^\"]*)\"");
      for (std::sregex_iterator e(text.begin(), text.end(), element), end;
           e != end;
           ++e)
        {
          Array             a;
          const std::string head = (*e)[1];
          for (std::sregex_iterator k(head.begin(), head.end(), attribute);
               k != std::sregex_iterator();
               ++k)
            a.attributes[(*k)[1]] = (*k)[2];
          a.type = a.attributes["type"];
          if (a.attributes.count("NumberOfComponents"))
            a.components = std::stoi(a.attributes["NumberOfComponents"]);
          // Binary arrays are decoded; others (e.g. deal.II's ASCII
          // FieldData TIME) are kept as text in bytes.
          a.bytes = a.attributes["format"] == "binary" ? decode((*e)[2])
                                                       : std::string((*e)[2]);
          const std::string name
            = a.attributes.count("Name") ? a.attributes["Name"] : "Points";
          arrays[name] = a;
        }
    }

    /// Header entry @p i of @p bytes.
    std::uint64_t
    entry(const std::string &bytes, const std::size_t i) const
    {
      std::uint64_t v = 0;
      if (word == 8)
        std::memcpy(&v, bytes.data() + 8 * i, 8);
      else
        {
          std::uint32_t w = 0;
          std::memcpy(&w, bytes.data() + 4 * i, 4);
          v = w;
        }
      return v;
    }

    /// The bytes of a DataArray's content.
    std::string
    decode(const std::string &content) const
    {
      if (!compressed)
        {
          // Byte count and bytes, encoded together.
          const std::string all = base64_decode(content);
          EXPECT_EQ(entry(all, 0) + word, all.size());
          return all.substr(word);
        }
#ifdef DEAL_II_WITH_ZLIB
      // The header (3 + number of blocks entries) is encoded on its own,
      // then the zlib streams of the blocks.
      const std::size_t first        = 4 * ((3 * word + 2) / 3);
      const std::string start        = base64_decode(content.substr(0, first));
      const std::size_t n_blocks     = entry(start, 0);
      const std::size_t header_chars = 4 * ((word * (3 + n_blocks) + 2) / 3);
      const std::string header = base64_decode(content.substr(0, header_chars));
      const std::string data   = base64_decode(content.substr(header_chars));
      std::string       out;
      std::size_t       at = 0;
      for (std::size_t b = 0; b < n_blocks; ++b)
        {
          const std::size_t size = entry(header, 3 + b);
          uLongf            n    = (b + 1 == n_blocks && entry(header, 2) != 0)
                                     ? entry(header, 2)
                                     : entry(header, 1);
          std::string       block(n, '\0');
          EXPECT_EQ(uncompress(reinterpret_cast<Bytef *>(block.data()),
                               &n,
                               reinterpret_cast<const Bytef *>(data.data()
                                                               + at),
                               size),
                    Z_OK);
          out += block.substr(0, n);
          at += size;
        }
      EXPECT_EQ(at, data.size());
      return out;
#else
      ADD_FAILURE() << "compressed file without zlib";
      return {};
#endif
    }

    /// The array @p name (an empty one, and a test failure, if missing).
    const Array &
    operator[](const std::string &name) const
    {
      const auto a = arrays.find(name);
      EXPECT_NE(a, arrays.end()) << "no DataArray " << name;
      static const Array none;
      return a == arrays.end() ? none : a->second;
    }
  };
} // namespace rockdda::test

#endif
