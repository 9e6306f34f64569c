/*
 * rosserial over Wi-Fi (ESP8266 / ESP32): publishes "hello world!" on `chatter` once a second
 * through rosserial_server's socket_node (roslaunch rosserial_server socket.launch) on the
 * computer at `server`, TCP port 11411.
 */
#if defined(ESP32)
#include <WiFi.h>
#else
#include <ESP8266WiFi.h>
#endif
#include <ros.h>
#include <std_msgs/String.h>

const char *ssid = "your-network";
const char *password = "your-password";
IPAddress server(192, 168, 1, 100);   // the computer running socket_node
const uint16_t serverPort = 11411;

ros::NodeHandle nh;
std_msgs::String str_msg;
ros::Publisher chatter("chatter", &str_msg);
char hello[13] = "hello world!";

void setup()
{
  Serial.begin(115200);
  WiFi.begin(ssid, password);
  while (WiFi.status() != WL_CONNECTED)
    delay(500);
  Serial.print("IP address: ");
  Serial.println(WiFi.localIP());
  nh.getHardware()->setConnection(server, serverPort);
  nh.initNode();
  nh.advertise(chatter);
}

void loop()
{
  if (nh.connected())
  {
    str_msg.data = hello;
    chatter.publish(&str_msg);
  }
  nh.spinOnce();
  delay(1000);
}
