"""Photos (paper Sec. 4, beyond it): the subject, its outline, its inner lines and its dark dots."""
