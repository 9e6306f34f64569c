"""Process handling lives in course_runtime.proc (the graders and demos run with it); this name
stays for the tests that import it from here."""
from course_runtime.proc import *  # noqa: F401,F403
from course_runtime.proc import descendants, kill_remembered  # noqa: F401
