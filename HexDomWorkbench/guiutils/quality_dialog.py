"""Non-modal dialog with a quality report: the text table and a scaled-Jacobian histogram per cell
type, drawn with QPainter (no plotting library needed)."""

from PySide import QtCore, QtGui

import FreeCADGui

from ..report import HISTOGRAM_BINS

_SERIES = (("hex", "hex", (64, 133, 230)), ("prism", "prism", (255, 153, 26)),
           ("tet", "tet", (204, 51, 204)))

_open_dialogs = []  # keeps non-modal dialogs alive until closed


class HistogramWidget(QtGui.QWidget):
    """Grouped bars: count of cells per scaled-Jacobian bin [-1, 1] and per type."""

    def __init__(self, report, parent=None):
        super().__init__(parent)
        self.series = [(label, list(report[key].get("histogram", [0] * HISTOGRAM_BINS)), rgb)
                       for key, label, rgb in _SERIES if report[key]["count"]]
        self.setMinimumSize(480, 220)

    def paintEvent(self, event):
        p = QtGui.QPainter(self)
        p.fillRect(self.rect(), QtGui.QColor(255, 255, 255))
        left, right, top, bottom = 40, 22, 24, 28
        w, h = self.width() - left - right, self.height() - top - bottom
        peak = max([max(hist) for _, hist, _ in self.series] + [1])
        p.setPen(QtGui.QColor(0, 0, 0))
        p.drawLine(left, top + h, left + w, top + h)
        p.drawLine(left, top, left, top + h)
        p.drawText(2, top + 8, str(peak))
        p.drawText(2, top + h, "0")
        bin_w = w / HISTOGRAM_BINS
        for b in range(0, HISTOGRAM_BINS + 1, 5):
            x = left + b * bin_w
            p.drawLine(int(x), top + h, int(x), top + h + 4)
            p.drawText(int(x) - 12, top + h + 18, "{:+.1f}".format(-1.0 + 0.1 * b))
        n = max(len(self.series), 1)
        for s, (label, hist, rgb) in enumerate(self.series):
            color = QtGui.QColor(*rgb)
            p.setBrush(color)
            p.setPen(QtCore.Qt.NoPen)
            for b, count in enumerate(hist[:HISTOGRAM_BINS]):
                if count:
                    bh = h * count / peak
                    x = left + b * bin_w + s * bin_w / n
                    p.drawRect(QtCore.QRectF(x, top + h - bh, bin_w / n, bh))
            p.fillRect(QtCore.QRectF(left + 10 + 70 * s, 6, 12, 12), color)
            p.setPen(QtGui.QColor(0, 0, 0))
            p.drawText(left + 26 + 70 * s, 17, label)
        p.end()


class QualityDialog(QtGui.QDialog):
    def __init__(self, label, report, text, parent=None):
        super().__init__(parent)
        self.setObjectName("HexDomQualityDialog")
        self.setWindowTitle("HexDom quality: " + label)
        layout = QtGui.QVBoxLayout(self)
        self.histogram = HistogramWidget(report, self)
        layout.addWidget(self.histogram)
        self.text = QtGui.QPlainTextEdit(self)
        self.text.setReadOnly(True)
        self.text.setFont(QtGui.QFontDatabase.systemFont(QtGui.QFontDatabase.FixedFont))
        self.text.setPlainText(text)
        layout.addWidget(self.text)
        buttons = QtGui.QDialogButtonBox(QtGui.QDialogButtonBox.Close, parent=self)
        buttons.rejected.connect(self.close)
        layout.addWidget(buttons)
        self.resize(640, 560)
        self.setAttribute(QtCore.Qt.WA_DeleteOnClose)
        self.finished.connect(lambda _result: _forget(self))


def _forget(dialog):
    if dialog in _open_dialogs:
        _open_dialogs.remove(dialog)


def show_quality_dialog(label, report, text):
    dialog = QualityDialog(label, report, text, FreeCADGui.getMainWindow())
    _open_dialogs.append(dialog)
    dialog.show()
    return dialog
