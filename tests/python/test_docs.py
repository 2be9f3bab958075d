"""The documentation site: built with warnings as errors, then looked at in headless Chromium.

docs/build.py builds the site (Sphinx, numpydoc, sphinx-gallery, myst-parser) from a staged copy into a tmp dir;
the gallery's examples run during the build. Chromium (Debian's chromium + chromium-driver, driven by selenium
with the system driver: nothing is downloaded) then opens the index, an API page, the gallery's index (its
thumbnails) and every gallery page and
checks that every image loaded (complete, naturalWidth > 0), that each gallery page shows its figures, and that
no link inside the site from those pages is broken (target file and anchor). Screenshots (PNG) of each page go to
the test's tmp dir, and to $FRICTIONSIM_DOCS_SCREENSHOTS when it is set.

Skipped when Sphinx, selenium, Chromium or what the examples import (dask, pint, xarray + h5netcdf: the extras
dask, units, io) is missing, except under CI (env CI set): then it fails, naming what is missing, so CI never skips
it silently. One build for the module: 50-57 s, the whole file 66-74 s, with the 8 examples on two cores at load 8.
"""

from __future__ import annotations

import importlib.util
import os
import re
import time
from pathlib import Path
from urllib.parse import unquote, urlparse

import pytest

REPO = Path(__file__).resolve().parents[2]
CHROMIUM = os.environ.get("FRICTIONSIM_CHROMIUM", "/usr/bin/chromium")
CHROMEDRIVER = os.environ.get("FRICTIONSIM_CHROMEDRIVER", "/usr/bin/chromedriver")
GALLERY = sorted((REPO / "examples" / "gallery").glob("plot_*.py"))
#: What the gallery's examples import beyond frictionsim's own dependencies: dask.distributed (the sweep), pint (field
#: units), xarray + h5netcdf on h5py (the netCDF example): the extras dask, units and io.
GALLERY_NEEDS = ("distributed", "pint", "xarray", "h5netcdf", "h5py")
API_PAGE = "generated/frictionsim.torsional.html"  # a module page: its table links into the class/function pages


def _missing() -> list:
    missing = [name for name in ("sphinx", "numpydoc", "sphinx_gallery", "myst_parser", "selenium") + GALLERY_NEEDS
               if importlib.util.find_spec(name) is None]
    missing += [path for path in (CHROMIUM, CHROMEDRIVER) if not os.access(path, os.X_OK)]
    if not (REPO / "docs" / "build.py").is_file():
        missing.append(str(REPO / "docs" / "build.py"))
    return missing


def _require_tools() -> None:
    missing = _missing()
    if not missing:
        return
    message = ("documentation test needs: " + ", ".join(missing)
               + " (pip install '.[test]': the docs, dask, io and units extras and selenium; "
               "apt-get install chromium chromium-driver)")
    if os.environ.get("CI"):
        pytest.fail(message + "; CI must not skip this test")
    pytest.skip(message)


def _builder():
    spec = importlib.util.spec_from_file_location("frictionsim_docs_build", REPO / "docs" / "build.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """(html directory, build seconds, sphinx output): one build with -W --keep-going."""
    _require_tools()
    root = tmp_path_factory.mktemp("docs")
    started = time.perf_counter()
    done = _builder().build(root / "html", stage_dir=root / "stage")
    elapsed = time.perf_counter() - started
    assert done.returncode == 0, (f"sphinx-build failed ({done.returncode}):\n"
                                  f"{done.stdout[-4000:]}\n{done.stderr[-8000:]}")
    return root / "html", elapsed, done.stdout + done.stderr


@pytest.fixture(scope="module")
def browser():
    _require_tools()
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--hide-scrollbars", "--window-size=1280,1000", "--force-device-scale-factor=1"):
        options.add_argument(argument)
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SE_OFFLINE", "true")  # selenium-manager must not fetch a browser or a driver
        driver = webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=options)
    driver.set_page_load_timeout(60)
    yield driver
    driver.quit()


def _screenshot_dirs(tmp_path: Path) -> list:
    dirs = [tmp_path / "screenshots"]
    if os.environ.get("FRICTIONSIM_DOCS_SCREENSHOTS"):
        dirs.append(Path(os.environ["FRICTIONSIM_DOCS_SCREENSHOTS"]))
    for d in dirs:
        d.mkdir(parents=True, exist_ok=True)
    return dirs


def _open(driver, page: Path) -> None:
    driver.get(page.as_uri())
    for _ in range(100):  # images are local: 'complete' within a few seconds
        if driver.execute_script("return document.readyState === 'complete' && "
                                 "Array.from(document.images).every(i => i.complete)"):
            return
        time.sleep(0.1)


def _images(driver) -> list:
    return driver.execute_script(
        "return Array.from(document.images).map(i => ({src: i.getAttribute('src'), complete: i.complete,"
        " width: i.naturalWidth, height: i.naturalHeight, cls: i.className}))")


def _save_screenshot(driver, name: str, dirs: list) -> list:
    """A full-page PNG (the window grown to the page's height, at most 8000 px)."""
    height = int(driver.execute_script("return Math.max(document.body.scrollHeight, "
                                       "document.documentElement.scrollHeight)"))
    driver.set_window_size(1280, min(max(height, 800), 8000))
    paths = []
    for d in dirs:
        path = d / f"{name}.png"
        assert driver.save_screenshot(str(path)), path
        paths.append(path)
    driver.set_window_size(1280, 1000)
    return paths


def _internal_links(driver, html: Path) -> list:
    """(href, file, fragment) of every link on the page that points into the built site."""
    hrefs = driver.execute_script("return Array.from(document.querySelectorAll('a[href]')).map(a => a.href)")
    links = []
    for href in hrefs:
        url = urlparse(href)
        if url.scheme != "file":
            continue
        target = Path(unquote(url.path))
        if html == target or html in target.parents:
            links.append((href, target, unquote(url.fragment)))
    return links


def _broken(links: list) -> list:
    broken, texts = [], {}
    for href, target, fragment in links:
        if not target.is_file():
            broken.append(f"{href}: no such file")
            continue
        if fragment and target.suffix == ".html":
            text = texts.setdefault(target, target.read_text(encoding="utf-8"))
            if not re.search(r'\bid="%s"' % re.escape(fragment), text):
                broken.append(f"{href}: no element with id {fragment!r}")
    return broken


def _not_blank(path: Path) -> bool:
    """The screenshot shows something: more than one colour in it."""
    from PIL import Image

    with Image.open(path) as image:
        extrema = image.convert("L").getextrema()
    return extrema[1] - extrema[0] > 50


def test_the_checks_see_a_broken_image_and_a_broken_link(browser, tmp_path):
    """The checks below can fail: a missing image is not 'rendered', a link to a missing page or anchor is
    broken, a blank screenshot is blank."""
    from PIL import Image

    Image.new("RGB", (40, 30), (200, 30, 30)).save(tmp_path / "red.png")
    (tmp_path / "there.html").write_text('<p id="here">target</p>', encoding="utf-8")
    page = tmp_path / "page.html"
    page.write_text('<img src="red.png"><img src="missing.png"><a href="there.html#here">ok</a>'
                    '<a href="there.html#nowhere">bad anchor</a><a href="gone.html">bad file</a>'
                    '<a href="https://example.org/">outside</a>', encoding="utf-8")
    _open(browser, page)
    rendered = {i["src"]: i["complete"] and i["width"] > 0 for i in _images(browser)}
    assert rendered == {"red.png": True, "missing.png": False}
    broken = _broken(_internal_links(browser, tmp_path))
    assert len(broken) == 2 and "nowhere" in broken[0] and "gone.html" in broken[1], broken
    assert not _not_blank(tmp_path / "red.png")  # one colour: blank
    assert _not_blank(_save_screenshot(browser, "probe", [tmp_path])[0])  # text and an image on white


def test_site_builds_without_warnings(site):
    html, elapsed, output = site
    assert "WARNING" not in output and "ERROR" not in output, output[-8000:]
    for page in ("index.html", "quickstart.html", "cpp.html", "architecture.html", "paper001_torsional_rig.html",
                 "api.html", API_PAGE, "gallery/index.html", "generated/frictionsim.units.html",
                 "generated/frictionsim.io.html", "generated/frictionsim.provenance.html"):
        assert (html / page).is_file(), page
    # the README's quick start and the architecture notes are in the site, not just linked
    assert "scripts/demo" in (html / "quickstart.html").read_text(encoding="utf-8")
    assert "find_package(frictionsim" in (html / "cpp.html").read_text(encoding="utf-8")
    # the API reference comes from the installed module: the engine's classes with their pybind11 docstrings
    dahl = (html / "generated" / "frictionsim.Dahl.html").read_text(encoding="utf-8")
    assert "tangential_stiffness" in dahl and "paper 000, eq 9" in dahl
    print(f"docs build: {elapsed:.1f} s")


def test_every_gallery_example_ran_and_made_figures(site):
    html, _, _ = site
    assert len(GALLERY) >= 8, [p.name for p in GALLERY]
    for example in GALLERY:
        page = html / "gallery" / f"{example.stem}.html"
        assert page.is_file(), page
        text = page.read_text(encoding="utf-8")
        figures = re.findall(r'<img[^>]+src="(\.\./_images/sphx_glr_%s_\d+\.png)"' % re.escape(example.stem), text)
        assert figures, f"{example.name}: no figure on its page"
        for src in figures:
            assert (page.parent / src).resolve().stat().st_size > 5000, src  # a real plot, not an empty canvas


def _output(page: Path) -> str:
    """The text an example printed on its page (the "Out" blocks), HTML entities decoded."""
    import html

    blocks = re.findall(r'<div class="sphx-glr-script-out[^"]*">.*?<pre>(.*?)</pre>', page.read_text(encoding="utf-8"),
                        re.S)
    return html.unescape(re.sub(r"<[^>]+>", "", "\n".join(blocks)))


def test_the_new_examples_show_what_they_claim(site):
    """The examples of fit comparison, field units and labelled output printed their results onto the page: the
    ranking with the generating law first, field units converted both ways, a netCDF file read back as an xarray
    Dataset with its provenance, and the rerun from the recorded repr bit for bit."""
    html, _, _ = site
    choose = _output(html / "gallery" / "plot_6_choose_friction_law.html")
    ranked = re.search(r"law_name.*?\nlaw\s*\n(\w+)", choose, re.S)
    assert ranked and ranked.group(1) == "dahl", choose[:1500]
    assert "wald_lower" in choose and "prediction error on the new drive" in choose
    well = _output(html / "gallery" / "plot_7_horizontal_well_field_units.html")
    assert "mud 10 ppg = 1198.3 kg/m^3" in well  # 1 ppg = 0.45359237 kg / 3.785411784 L = 119.826 kg/m^3
    assert "outer_diameter: expected a length (m), got 5 klbf [force]" in well
    assert re.search(r"best tool depth \d+ ft MD", well) and "zone of influence" in well
    labelled = _output(html / "gallery" / "plot_8_netcdf_provenance.html")
    assert "<xarray.Dataset>" in labelled and "frictionsim.provenance/1" in labelled
    assert "states bit-identical: True; solver counters equal: True" in labelled


def test_pages_render_in_chromium(site, browser, tmp_path):
    html, _, _ = site
    dirs = _screenshot_dirs(tmp_path)
    pages = [("index", html / "index.html"), ("api", html / API_PAGE), ("gallery", html / "gallery" / "index.html")]
    pages += [(f"gallery_{p.stem}", html / "gallery" / f"{p.stem}.html") for p in GALLERY]
    problems = []
    for name, page in pages:
        _open(browser, page)
        images = _images(browser)
        bad = [i for i in images if not (i["complete"] and i["width"] > 0 and i["height"] > 0)]
        problems += [f"{page.name}: image {i['src']} did not render" for i in bad]
        if name.startswith("gallery_"):
            figures = [i for i in images if "sphx-glr-single-img" in i["cls"] or "sphx-glr-multi-img" in i["cls"]]
            if not figures:
                problems.append(f"{page.name}: no gallery figure on the page")
            # a figure is at least a few hundred pixels wide as Chromium laid it out
            widths = browser.execute_script("return Array.from(document.querySelectorAll("
                                            "'img.sphx-glr-single-img, img.sphx-glr-multi-img')).map(i => i.width)")
            problems += [f"{page.name}: figure laid out {w} px wide" for w in widths if w < 200]
        if name != "index":
            problems += [f"{page.name}: {b}" for b in _broken(_internal_links(browser, html))]
        for path in _save_screenshot(browser, name, dirs):
            if not _not_blank(path):
                problems.append(f"{path}: blank screenshot")
    assert not problems, "\n".join(problems)
    shots = sorted(p.name for p in dirs[0].glob("*.png"))
    assert len(shots) == len(pages), shots
