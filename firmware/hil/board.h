/* What simulate.c and drive.c share: the emulated MCU and its clock. */
#ifndef HIL_BOARD_H
#define HIL_BOARD_H

#include <simavr/sim_avr.h>

#define F_CPU 16000000UL

extern avr_t *avr;
double sim_ms(void); /* simulated milliseconds since start */

/* drive.c: the space scanner's drive (L298N, motors, encoders, MPU6050) */
void drive_attach(void);
void drive_step(void);
void drive_set_load(double left, double right);

#endif
