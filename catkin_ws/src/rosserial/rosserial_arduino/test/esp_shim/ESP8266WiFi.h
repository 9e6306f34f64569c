// Host shim: the ESP8266 core's WiFi header (the same as the ESP32's here).
#include "WiFi.h"
