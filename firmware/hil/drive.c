/*
 * The space scanner's drive around the emulated Mega (see simulate.c): an L298N, two gear
 * motors, LM393 encoders and an MPU6050 on TWI, stepped by simulate.c's main loop.
 */
#include <math.h>
#include <stdio.h>

#include <simavr/avr_ioport.h>
#include <simavr/avr_twi.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_irq.h>

#include "board.h"

/* ---- the space scanner's drive: L298N, gear motors, LM393 encoders, MPU6050 ------------- */
/* ENA pin 4 = OC0B (PG5), IN1 5 = PE3, IN2 6 = PH3, IN3 7 = PH4, IN4 8 = PH5, ENB 9 = OC2B (PH6);
   encoders: left pin 2 = PE4 (INT4), right pin 3 = PE5 (INT5); MPU6050 at 0x68 on TWI. */
#define REG_PINE 0x2C
#define REG_PORTE 0x2E
#define REG_PORTG 0x34
#define REG_TCCR0A 0x44
#define REG_OCR0B 0x48
#define REG_TCCR2A 0xB0
#define REG_OCR2B 0xB4
#define REG_PORTH 0x102
#define WHEEL_MAX 15.0        /* rad/s at full duty, no load (12 V 120 rpm motor on a 14.8 V pack) */
#define MOTOR_TAU 0.08        /* s, speed time constant of motor + gearbox + wheel */
#define EDGES_PER_REV 40.0    /* 20-slot disc, both edges */
#define WHEEL_RADIUS 0.0325
#define TRACK 0.182

typedef struct wheel_t {
  double w;       /* rad/s, signed */
  double angle;   /* rad, for the encoder */
  double load;    /* 0..1: fraction of the torque taken by the load */
  int level;
  avr_irq_t *enc;
  const char *name;
} wheel_t;
static wheel_t wheels[2] = {{0, 0, 0, 0, NULL, "left"}, {0, 0, 0, 0, NULL, "right"}};
static uint64_t drive_last_cycle;
static double drive_next_report_ms;

static int bit(uint16_t reg, int b) { return (avr->data[reg] >> b) & 1; }

static double duty(int ch)   /* L298N enable input as a duty cycle 0..1 */
{
  if (ch == 0)
    return bit(REG_TCCR0A, 5) ? avr->data[REG_OCR0B] / 255.0 : bit(REG_PORTG, 5);
  return bit(REG_TCCR2A, 5) ? avr->data[REG_OCR2B] / 255.0 : bit(REG_PORTH, 6);
}

static int bridge(int ch)    /* +1 forward, -1 reverse, 0 brake/free */
{
  int a = ch == 0 ? bit(REG_PORTE, 3) : bit(REG_PORTH, 4);
  int b = ch == 0 ? bit(REG_PORTH, 3) : bit(REG_PORTH, 5);
  return a == b ? 0 : (a ? 1 : -1);
}

void drive_step(void)
{
  double dt = (avr->cycle - drive_last_cycle) / (double)F_CPU;
  drive_last_cycle = avr->cycle;
  if (dt <= 0)
    return;
  for (int ch = 0; ch < 2; ch++) {
    wheel_t *w = &wheels[ch];
    double target = bridge(ch) * duty(ch) * WHEEL_MAX * (1.0 - w->load);
    w->w += (target - w->w) * (1.0 - exp(-dt / MOTOR_TAU));
    w->angle += fabs(w->w) * dt;
    double edge = 2 * M_PI / EDGES_PER_REV;
    while (w->angle >= edge) {          /* the slotted disc: one pin change per edge */
      w->angle -= edge;
      w->level = !w->level;
      avr_raise_irq(w->enc, w->level);
    }
  }
  if (sim_ms() >= drive_next_report_ms && (wheels[0].w != 0 || wheels[1].w != 0)) {
    drive_next_report_ms = sim_ms() + 100;
    printf("motor %.3f %.3f %.3f %.3f %.1f\n", wheels[0].w, wheels[1].w,
           bridge(0) * duty(0), bridge(1) * duty(1), sim_ms());
    fflush(stdout);
  }
}

static uint8_t mpu_regs[128];
static uint8_t mpu_selected, mpu_ptr, mpu_first;
static avr_irq_t *twi_in;

static void mpu_put16(int reg, double v)
{
  if (v > 32767) v = 32767;
  if (v < -32768) v = -32768;
  int16_t x = (int16_t)lrint(v);
  mpu_regs[reg] = (uint8_t)((uint16_t)x >> 8);
  mpu_regs[reg + 1] = (uint8_t)(x & 0xFF);
}

static void mpu_update(void)
{
  double yaw_rate = WHEEL_RADIUS * (wheels[1].w - wheels[0].w) / TRACK;   /* rad/s */
  mpu_put16(0x3B, 0);                 /* accel x, y, z: level and still: 1 g on z */
  mpu_put16(0x3D, 0);
  mpu_put16(0x3F, 16384);
  mpu_put16(0x41, (25.0 - 36.53) * 340.0);   /* 25 degrees C */
  mpu_put16(0x43, 0);
  mpu_put16(0x45, 0);
  mpu_put16(0x47, yaw_rate * 180.0 / M_PI * 131.0);
  mpu_regs[0x75] = 0x68;              /* WHO_AM_I */
}

static void twi_hook(struct avr_irq_t *irq, uint32_t value, void *param)
{
  (void)irq; (void)param;
  avr_twi_msg_irq_t v;
  v.u.v = value;
  if (v.u.twi.msg & TWI_COND_STOP)
    mpu_selected = 0;
  if (v.u.twi.msg & TWI_COND_START) {
    mpu_selected = 0;
    if ((v.u.twi.addr >> 1) == 0x68) {
      mpu_selected = v.u.twi.addr;
      mpu_first = 1;
      mpu_update();
      avr_raise_irq(twi_in, avr_twi_irq_msg(TWI_COND_ACK, mpu_selected, 1));
    }
  }
  if (!mpu_selected)
    return;
  if (v.u.twi.msg & TWI_COND_WRITE) {
    avr_raise_irq(twi_in, avr_twi_irq_msg(TWI_COND_ACK, mpu_selected, 1));
    if (mpu_first) {
      mpu_ptr = v.u.twi.data & 0x7F;
      mpu_first = 0;
    } else {
      mpu_regs[mpu_ptr & 0x7F] = v.u.twi.data;
      mpu_ptr++;
    }
  }
  if (v.u.twi.msg & TWI_COND_READ) {
    avr_raise_irq(twi_in, avr_twi_irq_msg(TWI_COND_READ, mpu_selected, mpu_regs[mpu_ptr & 0x7F]));
    mpu_ptr++;
  }
}

void drive_set_load(double left, double right)
{
  wheels[0].load = left;
  wheels[1].load = right;
}

void drive_attach(void)
{
  wheels[0].enc = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('E'), 4);
  wheels[1].enc = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('E'), 5);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_TWI_GETIRQ(0), TWI_IRQ_OUTPUT), twi_hook,
                          NULL);
  twi_in = avr_io_getirq(avr, AVR_IOCTL_TWI_GETIRQ(0), TWI_IRQ_INPUT);
  mpu_update();
}
