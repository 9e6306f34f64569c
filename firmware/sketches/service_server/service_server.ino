/*
 * rosserial Service Server example: the device serves rosserial_arduino/Test on `test_srv`,
 * answering every call with its own counter.
 *   rosservice call /test_srv "input: 'hi'"
 */
#include <ros.h>
#include <rosserial_arduino/Test.h>

ros::NodeHandle nh;
using rosserial_arduino::Test;

int i = 0;
char reply[16];

void callback(const Test::Request &req, Test::Response &res)
{
  snprintf(reply, sizeof reply, "call %d", ++i);
  res.output = reply;
}

ros::ServiceServer<Test::Request, Test::Response> server("test_srv", &callback);

void setup()
{
  nh.initNode();
  nh.advertiseService(server);
}

void loop()
{
  nh.spinOnce();
  delay(10);
}
