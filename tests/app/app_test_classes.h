#pragma once
// The application's test classes (one .cpp each), run by test_main.cpp.
#include <QObject>

#include <memory>

#include "app/analysis/analysis_window.h"
#include "app/main_window/main_window.h"

namespace imagepro::app::test {

// Each appendix A panel's controls change the options the worker runs with.
class PanelTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void thresholdPanel();
  void edgeAndConnectivityPanels();
  void ellipsePanel();
  void rethresholdPanel();
  void reconstructionPanel();
  void trackingPanel();
  void applicationPanel();
  void displayPanels();
  void wheelScrollsThePanelNotItsValues();
  void settingsDialog();
  void listsComeFromTheEnumTables();
  void rangesComeFromTheSettingsTable();
 private:
  std::unique_ptr<MainWindow> window_;
};

// The worker thread on its own: frames, pending settings, latest frame wins.
class WorkerTest : public QObject {
  Q_OBJECT
 private slots:
  void latestFrameWins();
  void settingsApplyAtTheNextFrame();
  void reconstructsWithTheRunningSourcesCamera();
};

// Virtual input in the window: start / stop and the appendix A keys.
class VirtualTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void startStopProducesFrames();
  void keysMoveTheTarget();
  void keysInFieldsDoNotMoveTheTarget();
  void guiStaysResponsiveAtFullSpeed();
  void searchedRegionIsWholeBelowTheEllipseStage();
  void missingCameraShowsAnError();
  void constantVelocityFromTheSettingsDialog();
 private:
  std::unique_ptr<MainWindow> window_;
};

// File input: parameters shown, reprocessing on option changes, errors shown.
class FileTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void fileIsProcessedAndParametersShown();
  void optionChangeReprocessesTheFile();
  void folderIsInNaturalOrder();
  void folderIsSteppedWithKeysAndButtons();
  void startPlaysTheRestOfTheImages();
  void listFilePlaysInItsOrder();
  void missingFileShowsAnError();
  void recentFilesKeepOnlyWhatLoaded();
  void dialogsStartWhereTheUserLastWas();
  void droppedFilesAreOpenedAndRemembered();
  void samplesOpenFromTheMenu();
  void numbersSitBesideTheTarget();
  void longStatusIsWrappedNotCut();
  void resultsShowBothPosesOfADoubt();
 private:
  std::unique_ptr<MainWindow> window_;
};

// A change of source: nothing of the one before stays; the source is always named.
class SourceChangeTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void eachSourceShowsOnlyItsOwnState();
  void bannerGoesWhenALaterLoadSucceeds();
  void titleNamesTheSourceDataOutAndStream();
 private:
  std::unique_ptr<MainWindow> window_;
};

// The plots: one clock per source run, one window for the six charts, stills as points,
// round tick labels.
class PlotsTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void fileThenVirtualStartsOneClock();
  void sixChartsShareOneWindowWithRoundTicks();
  void aClockThatStartsAgainStartsThePlotsAgain();
  void stillsArePointsByTheirNumber();
 private:
  std::unique_ptr<MainWindow> window_;
};

// Screenshot and Data Out.
class OutputTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void screenshotWritesPng();
  void screenshotToBadPathShowsError();
  void screenshotFreezesProcessingWhileSaving();
  void dataOutWritesEveryFrame();
  void dataOutNeverOverwritesSilently();
  void dataOutTogglesWithCtrlD();
  void dataOutRefusesANameThatIsNotCsv();
  void streamFromTheDataOutPanel();
  void streamProblemIsNamedInTheStatusBar();
  void plotsRecordAndExport();
  void plotsRecordingIsBounded();
  void histogramChartFreesItsSeries();
 private:
  std::unique_ptr<MainWindow> window_;
};

// Save / Load / Restore defaults, and malformed files.
class SettingsFileTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void roundTrip();
  void malformedFileNamesTheKey();
  void thresholdNoneIsRefusedByItsKey();
  void aRenamedKeyLoadsWithAWarning();
  void unreadableFileIsAnError();
  void windowLayoutIsRemembered();
  void targetSetMenuChoosesTheFrames();
 private:
  std::unique_ptr<MainWindow> window_;
};

// The imagepro program's own command line.
class CommandLineTest : public QObject {
  Q_OBJECT
 private slots:
  void helpAndVersionNeedNoDisplay();
};

// The calibration wizard (thesis 4.6, appendix A): virtual pattern images, the run, Set and Use, errors;
// and its full intrinsic mode on rendered dot grids of a known camera.
class CalibrationWizardTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void recoversTheLensFromVirtualPatternImages();
  void aDistortionFreeLensIsNotDrawnAsOne();
  void quittingAsksBeforeLosingTheCalibration();
  void problemsAreNamedPerImageAndForTheRun();
  void aPatternTooSmallForTheImageIsRefused();
  void captureTakesTheRunningSourcesFrame();
  void panelAndMenuOpenTheWizard();
  void closingOrCancellingWhileRunningIsSafe();
  // The full intrinsic mode (intrinsics_page_test.cpp).
  void intrinsicModeRecoversTheCamera();
  void intrinsicModeNamesBadInput();
  void intrinsicModeCapturesTheRunningSource();
 private:
  std::unique_ptr<MainWindow> window_;
};

// The live calibration check (thesis A.1.1): the pattern's ideal spots and the spots found
// over the frame, against a rendered pattern's truth.
class CalibrationCheckTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void overlayMatchesThePatternsTruth();
  void withoutAPatternPoseItSaysWhy();
 private:
  std::unique_ptr<MainWindow> window_;
};

// The d0 dialog (thesis 4.1): virtual frames of known d0 at known distances, the chart of
// the iteration, Set d0, capture from the running source.
class D0DialogTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void virtualFramesGiveTheirKnownD0();
  void captureTakesTheRunningSourcesFrame();
 private:
  std::unique_ptr<MainWindow> window_;
};

// The Analysis window: both case studies (thesis 5.3) on virtual, recorded and live
// input, errors in words, and the GUI responsiveness measurement.
class AnalysisWindowTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void menuOpensTheWindow();
  void virtualPendulumGivesG();
  void harmonicFitFollowsThePendulum();
  void dataOutFileGivesTheCliNumbers();
  void stillAndSwingFilesGiveTheCliNumbers();
  void brokenFilesGiveNamedErrors();
  void virtualTwoTargetsHaveSmallErrors();
  void cancelStopsTheRun();
  void livePendulumIsCollected();
  void liveTwoTargetsNeedTwoTargets();
  void liveTwoTargetsFromImageFiles();
  void closingTheMainWindowWhileBusyIsSafe();
  void responsivenessProbeReports();
 private:
  std::unique_ptr<MainWindow> main_;
  std::unique_ptr<AnalysisWindow> window_;
};

// The Settings dialog's Camera device page (controls from a hand-made device, no camera,
// a device that cannot be opened), the camera on the command line, a missing camera started.
class CameraSettingsTest : public QObject {
  Q_OBJECT
 private slots:
  void init();
  void cleanup();
  void noCameraFoundAndTheRestWorks();
  void deviceThatCannotBeOpenedShowsItsStatus();
  void controlWidgetsFollowTheDevice();
  void missingCameraFromTheDialogIsNamedWhenStarted();
  void commandLineChoosesTheCamera();
  void captureCardInputAndStandard();
  void dialogEditsEachSourcesCamera();
 private:
  std::unique_ptr<MainWindow> window_;
};

}  // namespace imagepro::app::test
