// rosserial_arduino (re-implementation): the serial port a NodeHandle talks through.
// Default: `Serial` (UART0, the USB port of an Uno/Mega) at 57600 baud; setBaud() before
// initNode(). Define USE_USBCON for boards whose `Serial` is native USB (Leonardo, Micro).
#ifndef ROS_ARDUINO_HARDWARE_H_
#define ROS_ARDUINO_HARDWARE_H_

#include <Arduino.h>
#if defined(USE_USBCON)
#define SERIAL_CLASS Serial_
#else
#include <HardwareSerial.h>
#define SERIAL_CLASS HardwareSerial
#endif

class ArduinoHardware
{
public:
  ArduinoHardware(SERIAL_CLASS *io, long baud = 57600) : iostream(io), baud_(baud) {}
  ArduinoHardware() : iostream(&Serial), baud_(57600) {}
  ArduinoHardware(ArduinoHardware &h) : iostream(h.iostream), baud_(h.baud_) {}

  void setPort(SERIAL_CLASS *io) { iostream = io; }
  SERIAL_CLASS *getPort() { return iostream; }
  void setBaud(long baud) { baud_ = baud; }
  int getBaud() { return baud_; }

  void init()
  {
#if defined(USE_USBCON)
    // let the USB connection come up
    uint32_t start = millis();
    while (!(*iostream) && millis() - start < 3000)
    {
    }
#endif
    iostream->begin(baud_);
  }

  int read() { return iostream->read(); }
  void write(uint8_t *data, int length)
  {
    for (int i = 0; i < length; i++)
      iostream->write(data[i]);
  }
  unsigned long time() { return millis(); }

protected:
  SERIAL_CLASS *iostream;
  long baud_;
};

#endif
