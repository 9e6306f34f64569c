/*
 * Ultrasonic range finder (HC-SR04) published as sensor_msgs/Range on `ultrasound`
 * (practical work 7, self-study). TRIG on pin 11, ECHO on pin 12, 10 measurements a second.
 * Distance = echo time * speed of sound / 2.
 */
#include <ros.h>
#include <sensor_msgs/Range.h>

const int TRIG_PIN = 11;
const int ECHO_PIN = 12;
const float SOUND_SPEED = 343.0;      // m/s at 20 degrees C

ros::NodeHandle nh;
sensor_msgs::Range range_msg;
ros::Publisher pub_range("ultrasound", &range_msg);

char frameid[] = "ultrasound";
unsigned long range_timer = 0;

float measureRange()
{
  digitalWrite(TRIG_PIN, LOW);
  delayMicroseconds(2);
  digitalWrite(TRIG_PIN, HIGH);        // a 10 us pulse starts a measurement
  delayMicroseconds(10);
  digitalWrite(TRIG_PIN, LOW);
  unsigned long echo_us = pulseIn(ECHO_PIN, HIGH, 30000UL);   // 0 = no echo within 30 ms
  if (echo_us == 0)
    return range_msg.max_range + 1.0;  // out of range
  return echo_us * 1e-6 * SOUND_SPEED / 2.0;
}

void setup()
{
  pinMode(TRIG_PIN, OUTPUT);
  pinMode(ECHO_PIN, INPUT);
  nh.initNode();
  nh.advertise(pub_range);

  range_msg.radiation_type = sensor_msgs::Range::ULTRASOUND;
  range_msg.header.frame_id = frameid;
  range_msg.field_of_view = 0.26;      // about 15 degrees
  range_msg.min_range = 0.02;
  range_msg.max_range = 4.0;
}

void loop()
{
  if (millis() - range_timer >= 100)
  {
    range_msg.range = measureRange();
    range_msg.header.stamp = nh.now();
    pub_range.publish(&range_msg);
    range_timer = millis();
  }
  nh.spinOnce();
}
