// Host shim: the Arduino core's main loop.
void setup();
void loop();

int main()
{
  setup();
  for (;;)
    loop();
}
