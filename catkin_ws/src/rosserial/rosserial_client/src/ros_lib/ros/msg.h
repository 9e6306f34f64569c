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
    union { float real; uint32_t base; } u;
    u.real = f;
    return serializeUInt<uint32_t>(out, u.base);
  }

  static float deserializeFloat32(const unsigned char *in)
  {
    union { float real; uint32_t base; } u;
    u.base = deserializeUInt<uint32_t>(in);
    return u.real;
  }

  static int serializeFloat64(unsigned char *out, double d)
  {
    if (sizeof(double) == 4)
      return serializeAvrFloat64(out, (float)d);
    union { double real; uint64_t base; } u;
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
    union { double real; uint64_t base; } u;
    u.base = deserializeUInt<uint64_t>(in);
    return u.real;
  }

  // A 4-byte float (AVR's float and double) as an 8-byte IEEE 754 double on the wire.
  static int serializeAvrFloat64(unsigned char *o, const float &f)
  {
    union { float real; uint32_t base; } u;
    u.real = f;
    const uint32_t val = u.base;
    const uint32_t sign = val >> 31;
    int32_t exp = (int32_t)((val >> 23) & 0xFF);
    uint32_t mant = val & 0x7FFFFF;
    uint32_t hi, lo;
    if (exp == 0 && mant == 0)
    {
      hi = 0; lo = 0;                       // +-0
    }
    else if (exp == 0xFF)
    {
      hi = 0x7FF00000UL | (mant >> 3);      // inf / NaN
      lo = mant << 29;
    }
    else
    {
      if (exp == 0)                         // subnormal float: normalise
      {
        exp = 1;
        while (!(mant & 0x800000UL)) { mant <<= 1; --exp; }
        mant &= 0x7FFFFF;
      }
      const uint32_t e = (uint32_t)(exp - 127 + 1023);
      hi = (e << 20) | (mant >> 3);
      lo = mant << 29;
    }
    hi |= sign << 31;
    serializeUInt<uint32_t>(o, lo);
    serializeUInt<uint32_t>(o + 4, hi);
    return 8;
  }

  // An 8-byte IEEE 754 double from the wire into a 4-byte float (rounded, saturated).
  static int deserializeAvrFloat64(const unsigned char *i, float *f)
  {
    const uint32_t lo = deserializeUInt<uint32_t>(i);
    const uint32_t hi = deserializeUInt<uint32_t>(i + 4);
    const uint32_t sign = hi >> 31;
    const int32_t exp = (int32_t)((hi >> 20) & 0x7FF);
    uint32_t mant = ((hi & 0xFFFFFUL) << 3) | (lo >> 29);   // top 23 bits
    uint32_t out;
    if (exp == 0x7FF)
    {
      out = 0x7F800000UL | (mant ? (mant | 0x400000UL) : 0);
    }
    else
    {
      int32_t e = exp - 1023 + 127;
      if (exp == 0 || e <= 0)
        out = 0;                            // too small for a normal float: 0
      else if (e >= 0xFF)
        out = 0x7F800000UL;                 // too large: inf
      else
      {
        // round to nearest on the 29 dropped bits
        if ((lo & 0x1FFFFFFFUL) > 0x10000000UL ||
            ((lo & 0x1FFFFFFFUL) == 0x10000000UL && (mant & 1)))
        {
          if (++mant == 0x800000UL) { mant = 0; ++e; }
        }
        out = (e >= 0xFF) ? 0x7F800000UL : (((uint32_t)e << 23) | mant);
      }
    }
    out |= sign << 31;
    union { float real; uint32_t base; } u;
    u.base = out;
    *f = u.real;
    return 8;
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

  static int stringLength(const char *s)
  {
    return 4 + (s ? (int)strlen(s) : 0);
  }
};

}  // namespace ros

#endif
