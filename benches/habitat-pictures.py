#!/usr/bin/env python3
# Pictures of a champion in several habitats, for the results pages: a column per habitat,
# the body it grows there above (replay's creature.png; for a recording without one, the
# recording's first frame) and a moment of its walk there below (the middle frame of
# behaviour.gif), each column headed by its label. Needs Pillow.
#   ontogeny replay RUN --habitat A --fps 5 && ontogeny replay RUN --habitat B --fps 5
#   python3 benches/habitat-pictures.py OUT.png A=RUN/replay/gen-G-rank-1-A B=RUN/replay/gen-G-rank-1-B
# (any folder written by `replay` or `eval --record` serves: LABEL=FOLDER).
import sys
from pathlib import Path
from PIL import Image, ImageDraw, ImageFont
out, columns = sys.argv[1], []
for argument in sys.argv[2:]:
    label, folder = argument.split('=', 1)
    folder = Path(folder)
    gif = Image.open(folder / 'behaviour.gif')
    if (folder / 'creature.png').is_file():
        body = Image.open(folder / 'creature.png')
    else:
        gif.seek(0)
        body = gif.copy()
    body = body.convert('RGB').resize((720, 450))
    gif.seek(gif.n_frames // 2)
    walk = gif.convert('RGB').resize((720, 450))
    column = Image.new('RGB', (720, 930), 'white')
    column.paste(body, (0, 30))
    column.paste(walk, (0, 480))
    ImageDraw.Draw(column).text((10, 2), label, fill='black', font=ImageFont.load_default(size=24))
    columns.append(column)
picture = Image.new('RGB', (730 * len(columns) - 10, 930), 'white')
for k, column in enumerate(columns):
    picture.paste(column, (k * 730, 0))
picture.save(out, optimize=True)
