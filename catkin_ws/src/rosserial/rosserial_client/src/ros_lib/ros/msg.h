// rosserial client library (re-implementation): the base class of every generated message,
// little-endian field helpers and the AVR float64 conversion. No <cstring>, no STL: builds
// with avr-libc as is.
#ifndef ROS_MSG_H_
#define ROS_MSG_H_

#include <stdint.h>
#include <stddef.h>
#include <string.h>

namespace ros
{

class Msg
{
public:
  virtual ~Msg() {}
  virtual int serialize(unsigned char *outbuffer) const = 0;
  virtual int deserialize(unsigned char *data) = 0;
  virtual const char *getType() = 0;
  virtual const char *getMD5() = 0;
  // Bytes serialize() will write; lets the node handle refuse a message larger than its
  // buffer before writing it. -1 = unknown (hand-written messages).
  virtual int serializedLength() const { return -1; }

  template <typename U>
  static int serializeUInt(unsigned char *out, U v)
  {
    for (unsigned k = 0; k < sizeof(U); ++k)
      out[k] = (unsigned char)((v >> (8 * k)) & 0xFF);
    return sizeof(U);
  }

  template <typename U>
  static U deserializeUInt(const unsigned char *in)
  {
    U v = 0;
    for (unsigned k = 0; k < sizeof(U); ++k)
      v |= ((U)in[k]) << (8 * k);
    return v;
  }

  static int serializeFloat32(unsigned char *out, float f)
  {
    union
    {
      float real;
      uint32_t base;
    } u;
    u.real = f;
    return serializeUInt<uint32_t>(out, u.base);
  }

  static float deserializeFloat32(const unsigned char *in)
  {
    union
    {
      float real;
      uint32_t base;
    } u;
    u.base = deserializeUInt<uint32_t>(in);
    return u.real;
  }

  static int serializeFloat64(unsigned char *out, double d)
  {
    if (sizeof(double) == 4)
      return serializeAvrFloat64(out, (float)d);
    union
    {
      double real;
      uint64_t base;
    } u;
    u.real = d;
    return serializeUInt<uint64_t>(out, u.base);
  }

  static double deserializeFloat64(const unsigned char *in)
  {
    if (sizeof(double) == 4)
    {
      float f;
      deserializeAvrFloat64(in, &f);
      return f;
    }
    union
    {
      double real;
      uint64_t base;
    } u;
    u.base = deserializeUInt<uint64_t>(in);
    return u.real;
  }

  // A 4-byte float (AVR's float and double) as an 8-byte IEEE 754 double on the wire, as the
  // original widens it: exact (subnormal floats become normal doubles), inf/NaN kept, the sign
  // set only when f < 0 (so -0.0 goes out as +0.0 and NaN as a positive NaN).
  static int serializeAvrFloat64(unsigned char *o, const float f)
  {
    union
    {
      float real;
      uint32_t base;
    } u;
    u.real = f;
    int32_t exp = (int32_t)((u.base >> 23) & 0xFF);
    uint32_t mant = u.base & 0x7FFFFFUL;
    if (exp == 0xFF)
      exp = 0x7FF;  // inf / NaN
    else if (exp != 0)
      exp += 1023 - 127;  // normal
    else if (mant != 0)
    {
      exp = 1023 - 126;  // subnormal float: normalise
      while (!(mant & 0x800000UL))
      {
        mant <<= 1;
        --exp;
      }
      mant &= 0x7FFFFFUL;
    }
    uint32_t hi = ((uint32_t)exp << 20) | (mant >> 3);
    const uint32_t lo = mant << 29;
    if (f < 0)
      hi |= 0x80000000UL;
    serializeUInt<uint32_t>(o, lo);
    serializeUInt<uint32_t>(o + 4, hi);
    return 8;
  }

  // An 8-byte IEEE 754 double from the wire into a 4-byte float, as the original narrows it:
  // the top 24 mantissa bits kept and rounded half up to 23 (no carry into the exponent), too
  // large -> inf, below float's subnormal range -> 0, float-subnormal range shifted into a
  // subnormal float, inf/NaN kept, the sign copied.
  static int deserializeAvrFloat64(const unsigned char *i, float *f)
  {
    const uint32_t lo = deserializeUInt<uint32_t>(i);
    const uint32_t hi = deserializeUInt<uint32_t>(i + 4);
    int32_t exp = (int32_t)((hi >> 20) & 0x7FF);
    uint32_t mant = ((hi & 0xFFFFFUL) << 4) | (lo >> 28);  // top 24 bits
    const int32_t e = exp - 1023;
    if (exp == 0x7FF)
      exp = 0xFF;
    else if (e > 127)
    {
      exp = 0xFF;  // too large: inf
      mant = 0;
    }
    else if (e >= -126)
      exp = e + 127;  // normal
    else if (e < -150)
    {
      exp = 0;  // too small (or 0): 0
      mant = 0;
    }
    else
    {
      mant = (mant | 0x1000000UL) >> (-126 - e);  // a subnormal float
      exp = 0;
    }
    if (mant != 0xFFFFFFUL)
      mant += 1;  // round the 24th bit half up
    mant >>= 1;
    uint32_t out = mant | ((uint32_t)exp << 23) | (hi & 0x80000000UL);
    union
    {
      float real;
      uint32_t base;
    } u;
    u.base = out;
    *f = u.real;
    return 8;
  }

  // The original's little-endian helpers.
  template <typename A, typename V>
  static void varToArr(A arr, const V var)
  {
    for (size_t k = 0; k < sizeof(V); k++)
      arr[k] = (var >> (8 * k));
  }

  template <typename V, typename A>
  static void arrToVar(V &var, const A arr)
  {
    var = 0;
    for (size_t k = 0; k < sizeof(V); k++)
      var |= (arr[k] << (8 * k));
  }

  // Strings: length (uint32) then bytes. On receive the text is moved one byte down over the
  // length field and NUL-terminated in place, so a `const char*` field points into the input
  // buffer without copying.
  static int serializeString(unsigned char *out, const char *s)
  {
    const uint32_t n = s ? (uint32_t)strlen(s) : 0;
    serializeUInt<uint32_t>(out, n);
    if (n)
      memcpy(out + 4, s, n);
    return 4 + n;
  }

  static int deserializeString(unsigned char *in, const char **s)
  {
    const uint32_t n = deserializeUInt<uint32_t>(in);
    for (uint32_t k = 0; k < n; ++k)
      in[3 + k] = in[4 + k];
    in[3 + n] = 0;
    *s = (const char *)(in + 3);
    return 4 + n;
  }

  static int stringLength(const char *s) { return 4 + (s ? (int)strlen(s) : 0); }
};

}  // namespace ros

#endif
