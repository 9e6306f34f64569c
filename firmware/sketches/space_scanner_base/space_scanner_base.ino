/*
 * The diploma's Arduino Mega firmware (space scanner, section 2.4), re-written from its
 * description: two LM393 wheel encoders on the interrupt pins 2 (left) and 3 (right), CHANGE;
 * an L298N on pins 4-9 (ENA 4, IN1 5, IN2 6, IN3 7, IN4 8, ENB 9); a PID per wheel from the
 * measured wheel speed to the PWM duty; an MPU6050 on I2C published as sensor_msgs/Imu on
 * `imu/data_raw` every 100 ms; measured speeds (rad/s, std_msgs/Float64) on `motor_left_vel` /
 * `motor_right_vel`; set-points (whole rad/s, std_msgs/Int32) from `motor_left_cmd` /
 * `motor_right_cmd`; 57600 baud. Loop: encoder speed -> publish -> PID -> spinOnce, delay(1).
 * An encoder glitch (the same speed measured twice in a row while it should change) is
 * skipped; the gyro bias is the mean of 200 samples at rest taken in setup(); the accelerometer
 * is corrected by the diploma's ellipsoid calibration m = A^-1 (M - b) of accel_calibration.h
 * (the identity until `rosrun space_scanner_hw calibrate_accel` writes a fitted one).
 */
#include <ros.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int32.h>
#include <sensor_msgs/Imu.h>
#include <Wire.h>
#include "accel_calibration.h"

// ---- hardware ----------------------------------------------------------------------------
const uint8_t ENC_LEFT_PIN = 2, ENC_RIGHT_PIN = 3;
const uint8_t ENA = 4, IN1 = 5, IN2 = 6, IN3 = 7, IN4 = 8, ENB = 9;
const float EDGES_PER_REV = 40.0;          // 20-slot disc, both edges (CHANGE)
const unsigned long SPEED_PERIOD_MS = 50;  // speed updated every 50 ms
const uint8_t MPU_ADDR = 0x68;

class Encoder
{
public:
  explicit Encoder(uint8_t pin)
    : pin(pin), edges(0), edge_us(0), last_edges(0), last_edge_us(0), last_ms(0), vel(0),
      prev_raw(-1) {}
  void edge()   // interrupt: count the edge and remember when it came
  {
    edges++;
    edge_us = micros();
  }
  // Speed in rad/s from the edges of the last window and the time between the window's last
  // edge and the previous window's last edge (exact at constant speed, unlike counting edges
  // in a fixed window). The sign follows the commanded direction (one-channel encoder).
  void checkVel(int direction)
  {
    unsigned long now = millis();
    if (now - last_ms < SPEED_PERIOD_MS)
      return;
    last_ms = now;
    noInterrupts();
    long e = edges;
    unsigned long t = edge_us;
    interrupts();
    float raw;
    if (e == last_edges)
    {
      if (micros() - last_edge_us < 200000UL)
        return;                         // slow: keep the last value up to 200 ms
      raw = 0;
    }
    else
    {
      raw = (e - last_edges) * (2.0 * PI / EDGES_PER_REV) * 1e6 / (float)(t - last_edge_us);
      last_edges = e;
      last_edge_us = t;
    }
    if (raw != 0 && raw == prev_raw)   // glitch filter: a repeated reading is skipped
    {
      prev_raw = -1;
      return;
    }
    prev_raw = raw;
    vel = direction < 0 ? -raw : raw;
  }
  float getVel() const { return vel; }
  uint8_t pin;

private:
  volatile long edges;
  volatile unsigned long edge_us;
  long last_edges;
  unsigned long last_edge_us;
  unsigned long last_ms;
  float vel;
  float prev_raw;
};

class Motor   // one L298N channel
{
public:
  Motor(uint8_t en, uint8_t a, uint8_t b) : en(en), a(a), b(b), dir(1) {}
  void begin()
  {
    pinMode(en, OUTPUT);
    pinMode(a, OUTPUT);
    pinMode(b, OUTPUT);
    set(0);
  }
  void set(int pwm)   // -255..255
  {
    if (pwm > 255) pwm = 255;
    if (pwm < -255) pwm = -255;
    if (pwm != 0)
      dir = pwm > 0 ? 1 : -1;
    digitalWrite(a, pwm > 0 ? HIGH : LOW);
    digitalWrite(b, pwm < 0 ? HIGH : LOW);
    analogWrite(en, pwm < 0 ? -pwm : pwm);
  }
  int direction() const { return dir; }

private:
  uint8_t en, a, b;
  int dir;
};

class Pid
{
public:
  Pid(float kp, float ki, float kd) : kp(kp), ki(ki), kd(kd), integral(0), last_error(0), ff(17.0) {}
  // set-point and measurement in rad/s, dt in s; returns the PWM duty (-255..255)
  int control(float setpoint, float measured, float dt)
  {
    if (setpoint == 0)
    {
      integral = 0;
      last_error = 0;
      return 0;
    }
    if (dt <= 0)
      dt = 0.001;
    float error = setpoint - measured;
    integral += error * dt;
    if (integral > 200) integral = 200;
    if (integral < -200) integral = -200;
    float out = ff * setpoint + kp * error + ki * integral + kd * (error - last_error) / dt;
    last_error = error;
    if (out > 255) out = 255;
    if (out < -255) out = -255;
    return (int)out;
  }

private:
  float kp, ki, kd, integral, last_error, ff;
};

// ---- MPU6050 -----------------------------------------------------------------------------
float gyro_bias[3] = {0, 0, 0};

bool mpuRead(int16_t raw[7])   // ax ay az temp gx gy gz
{
  Wire.beginTransmission(MPU_ADDR);
  Wire.write(0x3B);
  if (Wire.endTransmission(false) != 0)
    return false;
  if (Wire.requestFrom(MPU_ADDR, (uint8_t)14) != 14)
    return false;
  for (int i = 0; i < 7; i++)
  {
    int hi = Wire.read();
    int lo = Wire.read();
    raw[i] = (int16_t)((hi << 8) | lo);
  }
  return true;
}

void setupImu()
{
  Wire.begin();
  Wire.beginTransmission(MPU_ADDR);
  Wire.write(0x6B);   // PWR_MGMT_1: wake up
  Wire.write(0);
  Wire.endTransmission();
  int16_t raw[7];
  long sum[3] = {0, 0, 0};
  int n = 0;
  for (int i = 0; i < 200; i++)
  {
    if (mpuRead(raw))
    {
      for (int k = 0; k < 3; k++)
        sum[k] += raw[4 + k];
      n++;
    }
  }
  for (int k = 0; k < 3 && n > 0; k++)
    gyro_bias[k] = (float)sum[k] / n;
}

// ---- ROS ---------------------------------------------------------------------------------
ros::NodeHandle nh;
sensor_msgs::Imu imu_msg;
std_msgs::Float64 lm, rm;
float setupVelL = 0, setupVelR = 0;

void leftWheelCB(const std_msgs::Int32 &lCb) { setupVelL = float(lCb.data); }
void rightWheelCB(const std_msgs::Int32 &rCb) { setupVelR = float(rCb.data); }

ros::Publisher leftWheelPublisher("motor_left_vel", &lm);
ros::Publisher rightWheelPublisher("motor_right_vel", &rm);
ros::Publisher imuPublisher("imu/data_raw", &imu_msg);
ros::Subscriber<std_msgs::Int32> leftWheelSubscriber("motor_left_cmd", &leftWheelCB);
ros::Subscriber<std_msgs::Int32> rightWheelSubscriber("motor_right_cmd", &rightWheelCB);

Encoder encL(ENC_LEFT_PIN), encR(ENC_RIGHT_PIN);
Motor motorL(ENA, IN1, IN2), motorR(ENB, IN3, IN4);
Pid leftPID(3.0, 15.0, 0.0), rightPID(3.0, 15.0, 0.0);
char imu_frame[] = "imu_link";

void encL_update() { encL.edge(); }
void encR_update() { encR.edge(); }

// the reading in m/s^2, M, corrected: m = A^-1 (M - b) (accel_calibration.h)
void accelCalibrated(const int16_t raw[7], float acc_lsb, float g, float out[3])
{
  float m[3];
  for (int k = 0; k < 3; k++)
    m[k] = raw[k] / acc_lsb * g - ACCEL_CAL_OFFSET[k];
  for (int i = 0; i < 3; i++)
    out[i] = ACCEL_CAL_MATRIX[i][0] * m[0] + ACCEL_CAL_MATRIX[i][1] * m[1] + ACCEL_CAL_MATRIX[i][2] * m[2];
}

void imuData()
{
  int16_t raw[7];
  if (!mpuRead(raw))
    return;
  const float G = 9.80665, ACC = 16384.0, GYRO = 131.0 * 180.0 / PI;   // +-2 g, +-250 deg/s
  imu_msg.header.stamp = nh.now();
  imu_msg.header.frame_id = imu_frame;
  float acc[3];
  accelCalibrated(raw, ACC, G, acc);
  imu_msg.linear_acceleration.x = acc[0];
  imu_msg.linear_acceleration.y = acc[1];
  imu_msg.linear_acceleration.z = acc[2];
  imu_msg.angular_velocity.x = (raw[4] - gyro_bias[0]) / GYRO;
  imu_msg.angular_velocity.y = (raw[5] - gyro_bias[1]) / GYRO;
  imu_msg.angular_velocity.z = (raw[6] - gyro_bias[2]) / GYRO;
  imu_msg.orientation_covariance[0] = -1;   // no orientation: imu/data_raw
}

unsigned long cTime = 0, imuTime = 0;

void setup()
{
  motorL.begin();
  motorR.begin();
  pinMode(ENC_LEFT_PIN, INPUT_PULLUP);
  pinMode(ENC_RIGHT_PIN, INPUT_PULLUP);
  attachInterrupt(digitalPinToInterrupt(encL.pin), encL_update, CHANGE);
  attachInterrupt(digitalPinToInterrupt(encR.pin), encR_update, CHANGE);
  nh.getHardware()->setBaud(57600);
  nh.initNode();
  nh.advertise(leftWheelPublisher);
  nh.advertise(rightWheelPublisher);
  nh.advertise(imuPublisher);
  nh.subscribe(leftWheelSubscriber);
  nh.subscribe(rightWheelSubscriber);
  setupImu();
  cTime = millis();
}

unsigned long pubTime = 0;

void loop()
{
  encL.checkVel(motorL.direction());
  encR.checkVel(motorR.direction());
  unsigned long now = millis();
  if (now - pubTime >= 20)   // 50 Hz: the 57600-baud line carries both speeds and the IMU
  {
    lm.data = encL.getVel();
    rm.data = encR.getVel();
    leftWheelPublisher.publish(&lm);
    rightWheelPublisher.publish(&rm);
    pubTime = now;
  }
  float dt = (now - cTime) * 0.001;
  motorL.set(leftPID.control(setupVelL, encL.getVel(), dt));
  motorR.set(rightPID.control(setupVelR, encR.getVel(), dt));
  nh.spinOnce();
  cTime = now;
  if (cTime - imuTime > 100)
  {
    imuData();
    imuPublisher.publish(&imu_msg);
    imuTime = cTime;
  }
  delay(1);
}
