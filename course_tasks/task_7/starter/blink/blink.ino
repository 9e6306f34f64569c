/*
 * Практическая работа 7, самостоятельное задание: светодиод на выводе 13 переключается
 * каждым сообщением std_msgs/Empty в топике toggle_led.
 * Practical work 7, self-study: toggle the LED on pin 13 on every message on `toggle_led`.
 */
#include <ros.h>
#include <std_msgs/Empty.h>

ros::NodeHandle nh;

void messageCb(const std_msgs::Empty &toggle_msg)
{
  // TODO: переключите светодиод (digitalWrite / digitalRead на LED_BUILTIN)
}

// TODO: объявите ros::Subscriber<std_msgs::Empty> на топик "toggle_led" с обработчиком messageCb

void setup()
{
  pinMode(LED_BUILTIN, OUTPUT);
  nh.initNode();
  // TODO: nh.subscribe(...)
}

void loop()
{
  nh.spinOnce();
  delay(1);
}
