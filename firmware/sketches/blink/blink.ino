/*
 * rosserial Subscriber example (practical work 7, self-study): every message on `toggle_led`
 * (std_msgs/Empty) toggles the LED on pin 13.
 *   rostopic pub toggle_led std_msgs/Empty --once
 */
#include <ros.h>
#include <std_msgs/Empty.h>

ros::NodeHandle nh;

void messageCb(const std_msgs::Empty &toggle_msg)
{
  digitalWrite(LED_BUILTIN, HIGH - digitalRead(LED_BUILTIN));  // blink the led
}

ros::Subscriber<std_msgs::Empty> sub("toggle_led", &messageCb);

void setup()
{
  pinMode(LED_BUILTIN, OUTPUT);
  nh.initNode();
  nh.subscribe(sub);
}

void loop()
{
  nh.spinOnce();
  delay(1);
}
