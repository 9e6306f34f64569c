/*
 * A workspace message and a service on the device: publishes rosserial_arduino/Adc (a message
 * of a catkin workspace package, not of Debian's ROS) on `adc` twice a second with the six
 * analog inputs A0..A5, and serves rosserial_arduino/Test on `test_srv` (output = the input
 * reversed). Integer parameter `~adc_offset` is added to every reading.
 */
#include <ros.h>
#include <rosserial_arduino/Adc.h>
#include <rosserial_arduino/Test.h>

ros::NodeHandle nh;
using rosserial_arduino::Test;

rosserial_arduino::Adc adc_msg;
ros::Publisher pub_adc("adc", &adc_msg);

char reply[64];

void reverse(const Test::Request &req, Test::Response &res)
{
  size_t n = strlen(req.input);
  if (n >= sizeof reply)
    n = sizeof reply - 1;
  for (size_t k = 0; k < n; k++)
    reply[k] = req.input[n - 1 - k];
  reply[n] = 0;
  res.output = reply;
}

ros::ServiceServer<Test::Request, Test::Response> server("test_srv", &reverse);

int offset = 0;
unsigned long last = 0;
bool have_param = false;

void setup()
{
  nh.initNode();
  nh.advertise(pub_adc);
  nh.advertiseService(server);
}

void loop()
{
  if (nh.connected() && !have_param)
  {
    have_param = true;
    if (!nh.getParam("~adc_offset", &offset))
      offset = 0;
  }
  if (millis() - last >= 500)
  {
    last = millis();
    adc_msg.adc0 = analogRead(A0) + offset;
    adc_msg.adc1 = analogRead(A1) + offset;
    adc_msg.adc2 = analogRead(A2) + offset;
    adc_msg.adc3 = analogRead(A3) + offset;
    adc_msg.adc4 = analogRead(A4) + offset;
    adc_msg.adc5 = analogRead(A5) + offset;
    pub_adc.publish(&adc_msg);
  }
  nh.spinOnce();
}
