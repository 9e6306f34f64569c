/*
 * Практическая работа 7, самостоятельное задание: ультразвуковой дальномер HC-SR04
 * (TRIG — вывод 11, ECHO — вывод 12) публикует sensor_msgs/Range в топик ultrasound 10 раз в
 * секунду. Расстояние = время эха * скорость звука / 2.
 * Practical work 7, self-study: an HC-SR04 (TRIG 11, ECHO 12) published as sensor_msgs/Range.
 */
#include <ros.h>
#include <sensor_msgs/Range.h>

const int TRIG_PIN = 11;
const int ECHO_PIN = 12;

ros::NodeHandle nh;
sensor_msgs::Range range_msg;
ros::Publisher pub_range("ultrasound", &range_msg);
char frameid[] = "ultrasound";

float measureRange()
{
  // TODO: импульс 10 мкс на TRIG_PIN, затем pulseIn(ECHO_PIN, HIGH, 30000UL) — время эха в мкс;
  //       верните расстояние в метрах (скорость звука 343 м/с)
  return 0.0;
}

void setup()
{
  pinMode(TRIG_PIN, OUTPUT);
  pinMode(ECHO_PIN, INPUT);
  nh.initNode();
  nh.advertise(pub_range);
  range_msg.radiation_type = sensor_msgs::Range::ULTRASOUND;
  range_msg.header.frame_id = frameid;
  range_msg.field_of_view = 0.26;
  range_msg.min_range = 0.02;
  range_msg.max_range = 4.0;
}

void loop()
{
  // TODO: каждые 100 мс (millis()) измерьте расстояние, заполните range и header.stamp = nh.now(),
  //       опубликуйте сообщение
  nh.spinOnce();
}
