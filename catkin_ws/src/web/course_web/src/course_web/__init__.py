"""course_web: the course in a browser (HTTP side; the page talks to rosbridge)."""
