"""Screenshots as arrays, read through Qt (Debian's PyQt5; no extra imaging library)."""
import numpy as np


def load_rgb(path):
    """PNG (or any format Qt reads) -> H x W x 3 uint8 array in RGB order."""
    from PyQt5.QtGui import QImage       # QImage needs no QApplication and no display
    img = QImage(str(path)).convertToFormat(QImage.Format_RGB32)
    if img.isNull():
        raise ValueError('cannot read image %s' % path)
    w, h, bpl = img.width(), img.height(), img.bytesPerLine()
    ptr = img.constBits()
    ptr.setsize(h * bpl)
    bgra = np.frombuffer(ptr, np.uint8).reshape(h, bpl // 4, 4)[:, :w, :3]
    return bgra[:, :, ::-1].copy()          # BGRA (little-endian RGB32) -> RGB
