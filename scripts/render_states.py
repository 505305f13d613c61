"""Renders deformed states of a run (mesh_states.xmf written by the app) to one PNG: a side view of the full
spatula (the half mesh and its mirror image) per state, coloured by the first stress invariant I1 = tr(sigma) / E, like the paper's Figs. 5 and 7.
The states' times are the load parameter (theta_y in degrees for a rotation, u_z in nm for a lift). Headless:

    scripts/render.sh scripts/render_states.py <output-dir>/mesh_states.xmf <picture.png> [--bottom] [time ...]

Without times, up to four states spread over the run are drawn; with times, the states nearest to them. --bottom
adds a view of the pad from below under each side view. `--field NAME` colours by another cell field than I1, on a
logarithmic scale over the three decades below its largest value over the states drawn (e.g. dissipated_by_friction
[J/m^2], where the pad has slid).
"""
import os
import sys
import tempfile

from paraview.simple import (Clip, ColorBy, CreateView, GetColorTransferFunction, GetScalarBar, Reflect, Render, SaveScreenshot, Show,
                             Text, Xdmf3ReaderS)
from paraview.simple import _DisableFirstRenderCameraReset
from PIL import Image

_DisableFirstRenderCameraReset()

arguments = [a for a in sys.argv[1:] if a != '--bottom']
bottom = '--bottom' in sys.argv
FIELD = 'I1'
if '--field' in arguments:
    at = arguments.index('--field')
    FIELD = arguments[at + 1]
    del arguments[at:at + 2]
DIVERGING = FIELD == 'I1'   # the stress invariant: a symmetric scale about zero; another field from zero up
xmf, png = os.path.abspath(arguments[0]), arguments[1]  # the reader resolves mesh.h5 from an absolute path only
reader = Xdmf3ReaderS(FileName=[xmf])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) if hasattr(reader.TimestepValues, '__len__') else [reader.TimestepValues]
if not times:
    sys.exit(f'{xmf}: no states')
if len(arguments) > 2:
    chosen = [min(times, key=lambda t: abs(t - float(wanted))) for wanted in arguments[2:]]
else:
    count = min(4, len(times))
    chosen = [times[round(i * (len(times) - 1) / max(count - 1, 1))] for i in range(count)]
full = Reflect(Input=reader, Plane='Y Min', CopyInput=1)
largest = 1e-12
for time in chosen:  # one colour scale for all panels
    full.UpdatePipeline(time)
    if FIELD not in full.CellData.keys():
        sys.exit(f'{xmf}: no cell field {FIELD} (fields: {", ".join(full.CellData.keys())})')
    largest = max(largest, *(abs(v) for v in full.CellData[FIELD].GetRange()))
if DIVERGING:
    largest *= 0.5  # a few elements at the pad's bend carry the extremes; saturate them to show the rest

width, height = 1400, 520


def panel(time, title, direction, up, focus, scale):
    """One view of the deformed state at `time` looking along `direction`."""
    view = CreateView('RenderView')
    view.ViewSize = [width, height]
    view.ViewTime = time
    if hasattr(view, 'UseColorPaletteForBackground'):
        view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    view.OrientationAxesVisibility = 1
    display = Show(full, view)
    display.SetRepresentationType('Surface With Edges')
    display.EdgeColor = [0.2, 0.2, 0.2]
    display.Ambient, display.Diffuse = 1.0, 0.0  # flat colours: the scale reads the same on every face
    ColorBy(display, ('CELLS', FIELD))
    lookup = GetColorTransferFunction(FIELD)
    lookup.ApplyPreset('Cool to Warm' if DIVERGING else 'Reds', True)
    if DIVERGING:
        lookup.RescaleTransferFunction(-largest, largest)
    else:   # three decades below the largest value, white at and below them (the untouched body stays light)
        lookup.InvertTransferFunction()
        lookup.RescaleTransferFunction(1e-3 * largest, largest)
        lookup.UseLogScale = 1
        lookup.NanColor = [1.0, 1.0, 1.0]
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lookup, view)
    bar.Title, bar.ComponentTitle = FIELD, ''
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    colour = 'I1 = tr(sigma) / E' if FIELD == 'I1' else FIELD
    label = Text(Text=f'state at load parameter {time:.2f}   ({title}, colour: {colour})')
    label_display = Show(label, view)
    label_display.Color = [0, 0, 0]
    label_display.FontSize = 14
    view.CameraViewUp = list(up)
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = list(focus)
    view.CameraPosition = [focus[i] + 4000 * direction[i] for i in range(3)]
    view.CameraParallelScale = scale
    Render(view)
    picture = os.path.join(tempfile.mkdtemp(), 'view.png')
    SaveScreenshot(picture, view, ImageResolution=[width, height])
    return Image.open(picture)


# The pad is the part of the body near its lowest point; it moves in X as the shaft turns about the end face, so
# the view from below is framed on it state by state.
pad = Clip(Input=full)
pad.ClipType = 'Plane'
pad.ClipType.Normal = [0.0, 0.0, 1.0]
pad.Invert = 1   # keep what lies below the plane
PAD_HEIGHT = 40.0   # nm above the lowest point


def pad_frame(time, bounds):
    pad.ClipType.Origin = [0.0, 0.0, bounds[4] + PAD_HEIGHT]
    pad.UpdatePipeline(time)
    low = pad.GetDataInformation().GetBounds()
    focus = ((low[0] + low[1]) / 2, 0.0, 0.0)
    return focus, 0.55 * max(low[3] - low[2], (low[1] - low[0]) * height / width)


pictures = []
for time in chosen:
    full.UpdatePipeline(time)
    bounds = full.GetDataInformation().GetBounds()
    centre = [(bounds[0] + bounds[1]) / 2, 0.0, (bounds[4] + bounds[5]) / 2]
    scale = 0.6 * max(bounds[5] - bounds[4], (bounds[1] - bounds[0]) * height / width)
    pictures.append(panel(time, 'side view from -Y', (0, -1, 0), (0, 0, 1), centre, scale))
    if bottom:   # the pad from below: where it adheres (the paper's lower rows of Figs. 7, 11, 14)
        focus, scale = pad_frame(time, bounds)
        pictures.append(panel(time, 'pad from below, -Z', (0, 0, -1), (0, -1, 0), focus, scale))

sheet = Image.new('RGB', (width, height * len(pictures)), 'white')
for i, picture in enumerate(pictures):
    sheet.paste(picture, (0, height * i))
sheet.save(png)
print('wrote', png, 'with states at', ', '.join(f'{t:.2f}' for t in chosen))
