#!/usr/bin/env python3
# Pictures of a champion in each of two habitats, for the results pages: the body it grows in
# each (replay's creature.png, top) and a moment of its walk there (the middle frame of
# replay's behaviour.gif, bottom), side by side, with the habitat's name. Needs Pillow.
#   ontogeny replay RUN --habitat A --fps 5 && ontogeny replay RUN --habitat B --fps 5
#   python3 benches/habitat-pictures.py RUN A B OUT.png
import sys
from pathlib import Path
from PIL import Image, ImageDraw, ImageFont
run, names, out = Path(sys.argv[1]), sys.argv[2:4], sys.argv[4]
columns = []
for name in names:
    folder = next((run / 'replay').glob(f'gen-*-rank-1-{name}'))
    body = Image.open(folder / 'creature.png').convert('RGB').resize((720, 450))
    gif = Image.open(folder / 'behaviour.gif')
    gif.seek(gif.n_frames // 2)
    walk = gif.convert('RGB').resize((720, 450))
    column = Image.new('RGB', (720, 930), 'white')
    column.paste(body, (0, 30))
    column.paste(walk, (0, 480))
    ImageDraw.Draw(column).text((10, 2), f'habitat: {name}', fill='black', font=ImageFont.load_default(size=24))
    columns.append(column)
picture = Image.new('RGB', (1450, 930), 'white')
for k, column in enumerate(columns):
    picture.paste(column, (k * 730, 0))
picture.save(out, optimize=True)
