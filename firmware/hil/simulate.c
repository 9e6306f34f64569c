/*
 * simulate: an Arduino Mega (ATmega2560, 16 MHz) on simavr for rosserial sketches.
 *
 *   simulate ELF [--speed X] [--distance CM] [--quiet]
 *
 * UART0 (Serial) is bridged to a pseudo-terminal; its path is the first line on stdout:
 *   pty: /dev/pts/N
 * Emulated around the MCU:
 *   - the LED on pin 13 (PB7): every change is reported on stdout as  "pin 13 <0|1> <ms>"
 *   - an HC-SR04 with TRIG on pin 11 (PB5) and ECHO on pin 12 (PB6): a trigger pulse is
 *     answered with an echo pulse of 2*distance/343 m/s (distance set by --distance or by the
 *     stdin command "distance CM"); each echo is reported as "echo <cm> <us> <ms>"
 *   - the space scanner's drive (sketches/space_scanner_base): an L298N (ENA 4, IN1 5, IN2 6,
 *     IN3 7, IN4 8, ENB 9) driving two gear motors (15 rad/s at full duty, 80 ms time constant,
 *     minus the load set by "load L R"), LM393 encoders with 40 edges a wheel turn on pins 2
 *     and 3, an MPU6050 at 0x68 on TWI (level, still, gyro z = the drive's yaw rate);
 *     every 100 ms while a wheel turns: "motor <wL> <wR> <dutyL> <dutyR> <ms>" (rad/s, -1..1)
 * Side channel: stdout lines (events, flushed) and stdin commands, one a line:
 *   distance CM      set the ultrasonic distance (cm)
 *   load L R         load on the left/right wheel, 0..1 of the motor's torque
 *   garbage N [SEED] N pseudo-random bytes to the host, spliced into the MCU's next rosserial
 *                    frame (fault injection; bytes and place fixed by SEED, default: the
 *                    number of garbage commands so far); reported as "garbage N <ms>"
 *   reset            reset the MCU (fault injection; the sketch starts over)
 *   quit             stop
 * Time: simulated time is paced to the wall clock times --speed (1 = real time, default;
 * 0 = as fast as possible). On exit, stderr gets "speed: R x real time (N cycles in S s)".
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <math.h>

#include <simavr/avr_ioport.h>
#include <simavr/avr_twi.h>
#include <simavr/avr_uart.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_irq.h>

#include "board.h"

#define SOUND_SPEED 343.0

avr_t *avr;
static int pty_master = -1, pty_slave = -1;
static volatile sig_atomic_t stop_requested;
static int uart_xon = 1;
static avr_irq_t *uart_in_irq;

static unsigned char in_buf[4096];   /* host -> MCU bytes waiting for the UART */
static size_t in_len, in_pos;

static double distance_cm = 100.0;
static uint64_t trig_rise_cycle;
static avr_irq_t *echo_irq;
static int quiet;

static double now_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

double sim_ms(void) { return avr->cycle * 1000.0 / F_CPU; }

static void on_signal(int sig) { (void)sig; stop_requested = 1; }

/* ---- UART0 <-> pty ---------------------------------------------------------------------- */

/* Fault injection ("garbage N [SEED]"): N bytes from rand_r(SEED) (default: the number of
   garbage commands so far), spliced into the MCU's next rosserial frame after its first
   garbage_at bytes (2..7, from the same seed: inside the frame's header) - so what the host
   gets is fixed by the seed and the stream, not by when the command arrived on the wall
   clock. A line silent for 100 ms of simulated time gets the bytes then. */
static unsigned char garbage_buf[4096];
static size_t garbage_len;
static int garbage_at;              /* bytes of the next frame before the garbage; 0 = none */
static unsigned garbage_count;
static uint64_t garbage_deadline;   /* cycle */
static int frame_pos = -1;          /* bytes of the current frame sent so far, -1 = between */
static unsigned char last_out;

static void emit(const unsigned char *p, size_t n)
{
  /* nobody listening and the pty buffer full: the bytes are lost, as on a real line */
  if (write(pty_master, p, n) < 0 && errno != EAGAIN && errno != EIO)
    perror("simulate: pty write");
}

static void garbage_flush(void)
{
  emit(garbage_buf, garbage_len);
  printf("garbage %d %.1f\n", (int)garbage_len, sim_ms());
  fflush(stdout);
  garbage_len = 0;
  garbage_at = 0;
}

static void garbage_queue(int n, unsigned seed)
{
  if (n < 0)
    n = 0;
  if (n > (int)sizeof garbage_buf)
    n = (int)sizeof garbage_buf;
  for (int i = 0; i < n; i++)
    garbage_buf[i] = (unsigned char)(rand_r(&seed) >> 7);
  garbage_len = (size_t)n;
  garbage_at = 2 + (int)(rand_r(&seed) % 6);
  garbage_deadline = avr->cycle + F_CPU / 10;
  frame_pos = -1;                   /* the next frame, not the rest of the current one */
}

static void uart_out_hook(struct avr_irq_t *irq, uint32_t value, void *param)
{
  (void)irq; (void)param;
  unsigned char b = (unsigned char)value;
  if (last_out == 0xFF && b == 0xFE)      /* rosserial's sync flag + protocol version 2 */
    frame_pos = 1;
  if (frame_pos >= 0)
    frame_pos++;
  last_out = b;
  emit(&b, 1);
  if (garbage_at && frame_pos == garbage_at)
    garbage_flush();
}

static void uart_xon_hook(struct avr_irq_t *irq, uint32_t value, void *param)
{
  (void)irq; (void)value; (void)param;
  uart_xon = 1;
}

static void uart_xoff_hook(struct avr_irq_t *irq, uint32_t value, void *param)
{
  (void)irq; (void)value; (void)param;
  uart_xon = 0;
}

static uint64_t next_in_cycle, xoff_since;

/* cycles one byte takes on the line (10 bits) at the baud rate the firmware set (UBRR0, U2X0) */
static uint64_t byte_cycles(void)
{
  unsigned ubrr = avr->data[0xC4] | ((avr->data[0xC5] & 0x0F) << 8);
  unsigned div = (avr->data[0xC0] & 0x02) ? 8 : 16;
  return 10ULL * div * (ubrr + 1);
}

/* Host bytes go in at the line's pace, never faster than the MCU's UART could receive them,
   and not while simavr's UART input FIFO signals XOFF (a lost XON is forgiven after 5 ms). */
static void pump_uart_in(void)
{
  if (in_pos == in_len) {
    in_pos = in_len = 0;
    ssize_t n = read(pty_master, in_buf, sizeof in_buf);
    if (n > 0)
      in_len = (size_t)n;
  }
  if (!uart_xon) {
    if (!xoff_since)
      xoff_since = avr->cycle;
    if (avr->cycle - xoff_since < F_CPU / 200)
      return;
    uart_xon = 1;
  }
  xoff_since = 0;
  while (uart_xon && in_pos < in_len && avr->cycle >= next_in_cycle) {
    avr_raise_irq(uart_in_irq, in_buf[in_pos++]);
    next_in_cycle = (next_in_cycle > avr->cycle ? next_in_cycle : avr->cycle) + byte_cycles();
  }
}

static int open_pty(char *name, size_t len)
{
  pty_master = posix_openpt(O_RDWR | O_NOCTTY);
  if (pty_master < 0 || grantpt(pty_master) || unlockpt(pty_master))
    return -1;
  if (ptsname_r(pty_master, name, len))
    return -1;
  /* keep the slave open ourselves: the pty survives the host closing and reopening it, and
     it is raw (no echo, no line editing) before the host configures it */
  pty_slave = open(name, O_RDWR | O_NOCTTY);
  if (pty_slave < 0)
    return -1;
  struct termios t;
  tcgetattr(pty_slave, &t);
  cfmakeraw(&t);
  cfsetspeed(&t, B57600);
  tcsetattr(pty_slave, TCSANOW, &t);
  fcntl(pty_master, F_SETFL, fcntl(pty_master, F_GETFL) | O_NONBLOCK);
  return 0;
}

/* ---- LED on pin 13 ------------------------------------------------------------------------ */

static void led_hook(struct avr_irq_t *irq, uint32_t value, void *param)
{
  (void)param;
  if (irq->value == value && irq->flags & IRQ_FLAG_INIT)
    return;
  printf("pin 13 %u %.1f\n", value ? 1 : 0, sim_ms());
  fflush(stdout);
}

/* ---- HC-SR04 ------------------------------------------------------------------------------ */

static avr_cycle_count_t echo_end(avr_t *a, avr_cycle_count_t when, void *param)
{
  (void)a; (void)when; (void)param;
  avr_raise_irq(echo_irq, 0);
  return 0;
}

static avr_cycle_count_t echo_start(avr_t *a, avr_cycle_count_t when, void *param)
{
  (void)when; (void)param;
  double us = 2.0 * distance_cm / 100.0 / SOUND_SPEED * 1e6;
  avr_raise_irq(echo_irq, 1);
  avr_cycle_timer_register_usec(a, (uint32_t)(us + 0.5), echo_end, NULL);
  if (!quiet) {
    printf("echo %.2f %.1f %.1f\n", distance_cm, us, sim_ms());
    fflush(stdout);
  }
  return 0;
}

static void trig_hook(struct avr_irq_t *irq, uint32_t value, void *param)
{
  (void)irq; (void)param;
  if (value) {
    trig_rise_cycle = avr->cycle;
  } else if (trig_rise_cycle && avr->cycle - trig_rise_cycle >= 8 * (F_CPU / 1000000)) {
    /* a trigger of >= 8 us (the datasheet asks for 10): the module bursts for ~450 us */
    trig_rise_cycle = 0;
    avr_cycle_timer_register_usec(avr, 450, echo_start, NULL);
  }
}


/* ---- stdin commands ----------------------------------------------------------------------- */

static char cmd_buf[256];
static size_t cmd_len;

static void handle_command(const char *line)
{
  double v, v2;
  if (sscanf(line, "distance %lf", &v) == 1) {
    distance_cm = v;
  } else if (sscanf(line, "garbage %lf", &v) == 1) {
    /* fault injection: v pseudo-random bytes into the next frame to the host (see above) */
    unsigned seed;
    if (sscanf(line, "garbage %*f %u", &seed) != 1)
      seed = ++garbage_count;
    garbage_queue((int)v, seed);
  } else if (strncmp(line, "reset", 5) == 0) {
    /* fault injection: the MCU resets (as by its reset button); the sketch starts over */
    avr_reset(avr);
    in_pos = in_len = 0;
    printf("reset %.1f\n", sim_ms());
    fflush(stdout);
  } else if (sscanf(line, "load %lf %lf", &v, &v2) == 2) {
    drive_set_load(v, v2);
  } else if (strncmp(line, "quit", 4) == 0) {
    stop_requested = 1;
  } else if (line[0]) {
    fprintf(stderr, "simulate: unknown command '%s' (distance CM | load L R | garbage N | reset | quit)\n", line);
  }
}

static void poll_stdin(void)
{
  char buf[256];
  ssize_t n = read(0, buf, sizeof buf);
  if (n == 0) {           /* stdin closed: keep running, just stop polling it */
    close(0);
    return;
  }
  for (ssize_t i = 0; i < n; i++) {
    if (buf[i] == '\n' || cmd_len == sizeof cmd_buf - 1) {
      cmd_buf[cmd_len] = 0;
      handle_command(cmd_buf);
      cmd_len = 0;
    } else {
      cmd_buf[cmd_len++] = buf[i];
    }
  }
}

/* simavr's messages go to stderr (stdout is the side channel), errors only (its timer
   warnings about Arduino's phase-correct PWM set-up would flood it) */
static void quiet_logger(avr_t *a, const int level, const char *format, va_list ap)
{
  (void)a;
  if (level <= LOG_ERROR)
    vfprintf(stderr, format, ap);
}

static void usage(void)
{
  fprintf(stderr, "usage: simulate ELF [--speed X] [--distance CM] [--quiet]\n");
  exit(2);
}

/* the command line: the ELF file; --speed, --distance and --quiet set as they go */
static const char *parse_args(int argc, char **argv, double *speed)
{
  const char *elf = NULL;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--speed") && i + 1 < argc) {
      *speed = atof(argv[++i]);
    } else if (!strcmp(argv[i], "--distance") && i + 1 < argc) {
      distance_cm = atof(argv[++i]);
    } else if (!strcmp(argv[i], "--quiet")) {
      quiet = 1;
    } else if (argv[i][0] == '-') {
      usage();
    } else if (!elf) {
      elf = argv[i];
    } else {
      usage();
    }
  }
  if (!elf)
    usage();
  return elf;
}

/* the ATmega2560 with the sketch loaded; 1 with a line on stderr when it cannot be made */
static int load_mcu(const char *elf)
{
  if (access(elf, R_OK)) {
    fprintf(stderr, "simulate: %s: %s\n", elf, strerror(errno));
    return 1;
  }
  avr_global_logger_set(quiet_logger);
  elf_firmware_t fw;
  memset(&fw, 0, sizeof fw);
  if (elf_read_firmware(elf, &fw)) {
    fprintf(stderr, "simulate: %s: not an AVR ELF file\n", elf);
    return 1;
  }
  avr = avr_make_mcu_by_name("atmega2560");
  if (!avr) {
    fprintf(stderr, "simulate: simavr has no atmega2560\n");
    return 1;
  }
  avr_init(avr);
  fw.frequency = F_CPU;
  fw.vcc = fw.avcc = fw.aref = 5000;   /* mV: a USB-powered Mega; analog inputs read 0 */
  avr_load_firmware(avr, &fw);
  avr->log = 0;
  return 0;
}

/* UART0 on a new pty (its path in `name`), the LED, the HC-SR04 and the drive; 1 when the
   pty cannot be made */
static int attach_io(char *name, size_t len)
{
  if (open_pty(name, len)) {
    perror("simulate: cannot create a pty");
    return 1;
  }
  /* UART0 */
  uint32_t flags = 0;
  avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
  flags &= ~AVR_UART_FLAG_STDIO;   /* not to simavr's own stdout */
  avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                          uart_out_hook, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON),
                          uart_xon_hook, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF),
                          uart_xoff_hook, NULL);
  uart_in_irq = avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
  /* pins */
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 7), led_hook, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 5), trig_hook, NULL);
  echo_irq = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 6);
  drive_attach();
  return 0;
}

/* the MCU runs until quit, a signal or a crash, paced to `speed` x real time; the exit
   status */
static int run_mcu(double speed)
{
  const double t0 = now_s();
  int state = cpu_Running;
  uint64_t next_check = 0, next_uart = 0;
  while (!stop_requested) {
    state = avr_run(avr);
    if (state == cpu_Done || state == cpu_Crashed)
      break;
    if (avr->cycle >= next_uart && (in_pos < in_len || avr->cycle >= next_check)) {
      next_uart = avr->cycle + F_CPU / 20000;   /* queued host bytes: every 50 us */
      pump_uart_in();
    }
    if (avr->cycle < next_check)
      continue;
    next_check = avr->cycle + F_CPU / 2000;   /* everything else every 0.5 ms */
    poll_stdin();
    if (garbage_at && avr->cycle >= garbage_deadline)
      garbage_flush();
    drive_step();
    if (speed > 0) {
      double ahead = avr->cycle / (double)F_CPU / speed - (now_s() - t0);
      if (ahead > 0.001) {
        struct pollfd p = {pty_master, POLLIN, 0};
        poll(&p, 1, (int)(ahead * 1000));
      }
    }
  }
  const double wall = now_s() - t0;
  fprintf(stderr, "speed: %.2f x real time (%llu cycles in %.2f s)\n",
          wall > 0 ? avr->cycle / (double)F_CPU / wall : 0.0,
          (unsigned long long)avr->cycle, wall);
  if (state == cpu_Crashed) {
    fprintf(stderr, "simulate: the MCU crashed at pc 0x%x\n", avr->pc);
    return 3;
  }
  return 0;
}

int main(int argc, char **argv)
{
  double speed = 1.0;
  const char *elf = parse_args(argc, argv, &speed);
  char name[128];
  if (load_mcu(elf) || attach_io(name, sizeof name))
    return 1;
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);
  signal(SIGPIPE, SIG_IGN);
  fcntl(0, F_SETFL, fcntl(0, F_GETFL) | O_NONBLOCK);

  printf("pty: %s\n", name);
  fflush(stdout);

  return run_mcu(speed);
}
