/*
 * ros_lib's time arithmetic and float64 on the 8-bit AVR (a double is 4 bytes here).
 *
 * - `arith` (std_msgs/String): the results of ros::Time / ros::Duration arithmetic and
 *   comparisons done on the MCU, as integers ("add 3 100000000 ..."), once a second.
 * - `float_in` (std_msgs/Float64) -> `float_out` (std_msgs/Float64): the value narrowed to the
 *   AVR's 4-byte double, multiplied by 2, widened back to the wire's 8 bytes.
 * - `stamp` (std_msgs/Time): nh.now() + 1.5 s, and `elapsed` (std_msgs/Duration): nh.now()
 *   minus the time of the first sync.
 */
#include <stdio.h>
#include <ros.h>
#include <ros/time.h>
#include <ros/duration.h>
#include <std_msgs/String.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Time.h>
#include <std_msgs/Duration.h>

ros::NodeHandle nh;

std_msgs::String arith_msg;
ros::Publisher arith("arith", &arith_msg);
std_msgs::Float64 out_msg;
ros::Publisher float_out("float_out", &out_msg);
std_msgs::Time stamp_msg;
ros::Publisher stamp("stamp", &stamp_msg);
std_msgs::Duration elapsed_msg;
ros::Publisher elapsed("elapsed", &elapsed_msg);

void onFloat(const std_msgs::Float64 &m)
{
  out_msg.data = m.data * 2;
  float_out.publish(&out_msg);
}
ros::Subscriber<std_msgs::Float64> float_in("float_in", &onFloat);

char text[200];
ros::Time first;

void setup()
{
  nh.initNode();
  nh.advertise(arith);
  nh.advertise(float_out);
  nh.advertise(stamp);
  nh.advertise(elapsed);
  nh.subscribe(float_in);
}

void loop()
{
  ros::Time add = ros::Time(1, 500000000UL) + ros::Duration(1, 600000000L);
  ros::Time wrap = ros::Time(0, 0) - ros::Duration(0, 500000000L);
  ros::Duration diff = ros::Time(3, 900000000UL) - ros::Time(5, 100000000UL);
  ros::Time t;
  t.fromNSec(1500000000L);
  ros::Time f;
  f.fromSec(12.25);
  ros::Duration scaled = ros::Duration(1, 500000000L) * 3.0;
  int cmp = (ros::Time(1, 5) < ros::Time(1, 6)) * 100 + (ros::Time(2, 0) > ros::Time(1, 9)) * 10 +
            (ros::Duration(-1, 0) < ros::Duration(0, 0));
  snprintf(text, sizeof(text),
           "add %lu %lu wrap %lu %lu diff %ld %ld nsec %lu %lu fsec %lu %lu scaled %ld %ld cmp %d "
           "tosec %ld double %u",
           (unsigned long)add.sec, (unsigned long)add.nsec, (unsigned long)wrap.sec,
           (unsigned long)wrap.nsec, (long)diff.sec, (long)diff.nsec, (unsigned long)t.sec,
           (unsigned long)t.nsec, (unsigned long)f.sec, (unsigned long)f.nsec, (long)scaled.sec,
           (long)scaled.nsec, cmp, (long)(ros::Time(7, 250000000UL).toSec() * 1000),
           (unsigned)sizeof(double));
  arith_msg.data = text;
  arith.publish(&arith_msg);
  if (nh.connected())
  {
    ros::Time now = nh.now();
    if (first.isZero())
      first = now;
    stamp_msg.data = now + ros::Duration(1, 500000000L);
    stamp.publish(&stamp_msg);
    elapsed_msg.data = now - first;
    elapsed.publish(&elapsed_msg);
  }
  for (int i = 0; i < 100; ++i)
  {
    nh.spinOnce();
    delay(10);
  }
}
